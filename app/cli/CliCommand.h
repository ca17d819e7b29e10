#ifndef bender_CliCommand_h
#define bender_CliCommand_h

// How a command plugs into bender-cli. Each Add function (one file per command) adds
// `bender-cli NAME` to `cli` (AddCommand in CliParsing.h: a CLI11 subcommand): its options,
// typed and checked by CLI11, its help (summary, details), and the function that runs it after
// a successful parse and returns the exit status (1 bad input or failure, 2 usage error).
//
// Adding a command: write `void AddXxxCommand(CLI::App& cli)` in CommandXxx.cxx (listed in
// app/cli/CMakeLists.txt), declare it here and add it to the table in CliCommands.cxx.

#include <iosfwd>

namespace CLI
{
class App;
}

namespace bender
{
void AddWarpCommand(CLI::App& cli);
void AddSegmentCommand(CLI::App& cli, std::ostream& out, std::ostream& err);
void AddPhantomCommand(CLI::App& cli, std::ostream& out, std::ostream& err);
void AddCheckCommand(CLI::App& cli);
void AddExportCommand(CLI::App& cli);
void AddRenderCommand(CLI::App& cli);
void AddCenterlineCommand(CLI::App& cli);
void AddMeasureCommand(CLI::App& cli);
void AddClipCommand(CLI::App& cli);
void AddCfdCaseCommand(CLI::App& cli);
void AddCfdVerifyCommand(CLI::App& cli);
/// bender-cli compare: built with the Qt application (its report is app/report, QPdfWriter).
void AddCompareCommand(CLI::App& cli);
void AddFormatsCommand(CLI::App& cli);
void AddIgtlSendCommand(CLI::App& cli);
void AddSweepCommand(CLI::App& cli);
// AddTrackerCommand: TrackerCommand.h (it also takes the USB back end of the tests).
} // namespace bender

#endif
