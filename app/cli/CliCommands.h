#ifndef bender_CliCommands_h
#define bender_CliCommands_h

#include <string>
#include <vector>

// Each bender-cli command: args are the words after the command's name. Returns the exit
// status. Every command answers --help / -h with its own usage on stdout and exit 0.
// Errors go to stderr as one line naming the input and the problem.

int RunWarpCommand(const std::vector<std::string>& args);
int RunSegmentCommand(const std::vector<std::string>& args);
int RunPhantomCommand(const std::vector<std::string>& args);
int RunTrackerCommand(const std::vector<std::string>& args);
int RunCheckCommand(const std::vector<std::string>& args);
int RunExportCommand(const std::vector<std::string>& args);
int RunRenderCommand(const std::vector<std::string>& args);

#endif
