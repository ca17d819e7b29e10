// bender-cli: the headless tool for batch work. The commands are in bender_cli_commands
// (CliCommands.h), which the tests run in-process.

#include "CliCommands.h"

#include <string>
#include <vector>

int main(int argc, char** argv)
{
  return bender::RunBenderCli(std::vector<std::string>(argv + 1, argv + argc));
}
