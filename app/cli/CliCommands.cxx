// The bender-cli application: its own options and the table of commands (main.cxx only
// forwards argv here).

#include "CliCommands.h"

#include "CliCommand.h"
#include "CliParsing.h"

#include "DataDirectory.h"
#include "TrackerCommand.h"

#include <filesystem>
#include <iostream>

namespace bender
{
namespace
{
// The commands, in the order of `bender-cli --help`.
void AddCommands(CLI::App& cli)
{
  AddWarpCommand(cli);
  AddSegmentCommand(cli, std::cout, std::cerr);
  AddPhantomCommand(cli, std::cout, std::cerr);
  AddCheckCommand(cli);
  AddExportCommand(cli);
  AddRenderCommand(cli);
  AddCenterlineCommand(cli);
  AddMeasureCommand(cli);
  AddClipCommand(cli);
  AddCfdCaseCommand(cli);
  AddCfdVerifyCommand(cli);
#ifdef BENDER_WITH_REPORT
  AddCompareCommand(cli);
#endif
  AddFormatsCommand(cli);
  AddTrackerCommand(cli, std::cout, std::cerr);
  AddIgtlSendCommand(cli);
  AddSweepCommand(cli);
}

void PrintDataDirectory()
{
  // Where the demo data is looked for (BENDER_DATA_DIR, else <bin>/../share/bender).
  const std::string dir = DataDirectory();
  std::error_code error;
  if (!std::filesystem::is_directory(std::filesystem::path(dir) / "demo", error))
  {
    std::cerr << "bender-cli: " << dir
              << ": no Bender data folder (demo/ missing); install Bender or set "
                 "BENDER_DATA_DIR\n";
    throw CLI::RuntimeError(1);
  }
  std::cout << dir << "\n";
  throw CLI::Success();
}

std::unique_ptr<CLI::App> NewBenderCli()
{
  std::unique_ptr<CLI::App> cli = NewCliApp();
  cli->footer("Run 'bender-cli COMMAND --help' for the options of a command.");
  cli->add_flag_callback(
    "--version",
    []
    {
      std::cout << "bender-cli 0.1.0\n";
      throw CLI::Success();
    },
    "print the version");
  cli->add_flag_callback("--data-dir",
    PrintDataDirectory,
    "print the folder where the demo data is looked for (BENDER_DATA_DIR, else "
    "<bin>/../share/bender)");
  AddCommands(*cli);
  for (CLI::App* command : cli->get_subcommands({}))
  {
    command->group("commands");
  }
  // `bender-cli help` is --help, as in git; hidden from the list (no group).
  CLI::App* tool = cli.get();
  cli->add_subcommand("help", "the help")
    ->group("")
    ->callback(
      [tool]
      {
        // The tool's own help (help() would give this subcommand's, now that it is chosen).
        std::cout << tool->get_formatter()->make_help(
          tool, tool->get_name(), CLI::AppFormatMode::Normal);
        throw CLI::Success();
      });
  cli->require_subcommand(1);
  return cli;
}
} // namespace

std::vector<std::string> CliCommandNames()
{
  const std::unique_ptr<CLI::App> cli = NewBenderCli();
  std::vector<std::string> names;
  for (const CLI::App* command : cli->get_subcommands({}))
  {
    if (!command->get_group().empty())
    {
      names.push_back(command->get_name());
    }
  }
  return names;
}

int RunBenderCli(const std::vector<std::string>& args)
{
  const int status = RunCli(*NewBenderCli(), args, std::cout, std::cerr);
  std::cout.flush();
  return status;
}

} // namespace bender
