#include "CliCommands.h"

#include <cstdio>
int RunWarpCommand(const std::vector<std::string>&)
{
  std::fprintf(stderr, "bender-cli warp: not available in this build\n");
  return 2;
}
