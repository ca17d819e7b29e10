// bender-cli segment / phantom: thin wrappers; the logic lives in modules/Segmentation.
#include "CliCommands.h"

#include "SegmentCommand.h"

#include <iostream>

int RunSegmentCommand(const std::vector<std::string>& args)
{
  return bender::RunSegmentCli(args, std::cout, std::cerr);
}

int RunPhantomCommand(const std::vector<std::string>& args)
{
  return bender::RunPhantomCli(args, std::cout, std::cerr);
}
