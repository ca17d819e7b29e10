// Placeholder, replaced by the module's owner.
#include "CliCommands.h"

#include <cstdio>
int RunSegmentCommand(const std::vector<std::string>&)
{
  std::fprintf(stderr, "bender-cli segment: not available in this build\n");
  return 2;
}
int RunPhantomCommand(const std::vector<std::string>&)
{
  std::fprintf(stderr, "bender-cli phantom: not available in this build\n");
  return 2;
}
