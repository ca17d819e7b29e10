#ifndef bender_CliCommands_h
#define bender_CliCommands_h

#include <string>
#include <vector>

// The bender-cli commands (library bender_cli_commands). Each command: args are the words after
// the command's name; returns the exit status (0 success, 1 bad input or processing error,
// 2 usage error). Every command answers --help / -h with its own usage on stdout and exit 0.
// Errors go to stderr as one line naming the input and the problem.
//
// Adding a command: write `int RunXxxCommand(const std::vector<std::string>& args)` in a new
// CommandXxx.cxx (listed in app/cli/CMakeLists.txt), declare it here and add one line to the
// table in CliCommands.cxx.

int RunWarpCommand(const std::vector<std::string>& args);
int RunSegmentCommand(const std::vector<std::string>& args);
int RunPhantomCommand(const std::vector<std::string>& args);
int RunTrackerCommand(const std::vector<std::string>& args);
int RunIgtlSendCommand(const std::vector<std::string>& args);
int RunCheckCommand(const std::vector<std::string>& args);
int RunExportCommand(const std::vector<std::string>& args);
int RunRenderCommand(const std::vector<std::string>& args);
int RunCenterlineCommand(const std::vector<std::string>& args);
int RunMeasureCommand(const std::vector<std::string>& args);
int RunClipCommand(const std::vector<std::string>& args);
int RunCfdCaseCommand(const std::vector<std::string>& args);

namespace bender
{
/// One entry of the command table.
struct CliCommand
{
  const char* name;
  const char* summary;
  int (*run)(const std::vector<std::string>&);
};

/// The command table, in the order of `bender-cli --help`.
const std::vector<CliCommand>& CliCommandTable();

/// The whole of bender-cli: args are argv[1..]. Dispatches to a command, prints the general
/// help, the version; never throws (an escaping exception becomes one line and exit 1).
int RunBenderCli(const std::vector<std::string>& args);
} // namespace bender

#endif
