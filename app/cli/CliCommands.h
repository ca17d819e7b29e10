#ifndef bender_CliCommands_h
#define bender_CliCommands_h

// bender-cli as a library (bender_cli_commands), so that the tests run it in-process. The
// commands and their options are CLI11 subcommands (CliCommand.h); every command answers
// -h/--help with its generated help on stdout and exit 0; errors go to stderr as one line
// naming the input and the problem. Exit status: 0 success, 1 bad input or processing error,
// 2 usage error.

#include <string>
#include <vector>

namespace bender
{
/// The names of the commands, in the order of `bender-cli --help`.
std::vector<std::string> CliCommandNames();

/// The whole of bender-cli: args are argv[1..]. Runs a command, prints the help, the version or
/// the data folder; never throws (an escaping exception becomes one line and exit 1).
int RunBenderCli(const std::vector<std::string>& args);
} // namespace bender

#endif
