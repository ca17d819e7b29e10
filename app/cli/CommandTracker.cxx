// bender-cli tracker: the command's arguments are read by RunTrackerCli (TrackerCommand.h),
// which the tests also run in-process with their own streams.
#include "CliCommand.h"
#include "CliParsing.h"

#include "TrackerCommand.h"

#include <iostream>
#include <memory>

void bender::AddTrackerCommand(CLI::App& cli)
{
  auto command = std::make_shared<CLI::App*>(nullptr);
  *command = AddCommand(cli,
    "tracker",
    "stream poses from a Polhemus Fastrak, OpenIGTLink, a recording or the simulator",
    "",
    [command] { return RunTrackerCli((*command)->remaining(), std::cout, std::cerr); });
  (*command)->prefix_command();
  (*command)->set_help_flag();
}
