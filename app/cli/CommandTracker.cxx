// Placeholder, replaced by the module's owner.
#include "CliCommands.h"

#include <cstdio>
int RunTrackerCommand(const std::vector<std::string>&)
{
  std::fprintf(stderr, "bender-cli tracker: not available in this build\n");
  return 2;
}
