// bender-cli tracker: the command's logic lives in modules/Tracking (TrackerCommand) so
// that the tests run it in-process.
#include "CliCommands.h"

#include "TrackerCommand.h"

#include <iostream>

int RunTrackerCommand(const std::vector<std::string>& args)
{
  return bender::RunTrackerCli(args, std::cout, std::cerr);
}
