#ifndef bender_CliParsing_h
#define bender_CliParsing_h

// Shared CLI11 set-up of the bender-cli commands: each command keeps its own usage text (printed
// for -h/--help on stdout, exit 0) and reports a usage error as one line
// "bender-cli <command>: <problem>" followed by the usage on stderr, exit 2.

#include "BenderErrors.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <string>
#include <vector>

namespace bender
{

/// A CLI::App for `bender-cli <command>` whose help flag is handled by ParseCommandLine.
class CommandLine
{
public:
  CommandLine(const std::string& command, const char* usage)
    : App("", "bender-cli " + command)
    , Command(command)
    , Usage(usage)
  {
    this->App.set_help_flag();
    this->App.add_flag("-h,--help", this->Help);
    this->App.allow_extras(false);
    this->App.positionals_at_end(false);
  }

  CLI::App App;

  /// Parses `args`. Returns -1 to go on, or the exit status to return now (0 after printing
  /// the usage for --help, 2 after a usage error).
  int Parse(const std::vector<std::string>& args)
  {
    try
    {
      // CLI11 consumes its argument vector from the back.
      std::vector<std::string> reversed(args.rbegin(), args.rend());
      this->App.parse(reversed);
    }
    catch (const CLI::ParseError& e)
    {
      if (this->Help)
      {
        std::fputs(this->Usage, stdout);
        return 0;
      }
      std::fprintf(
        stderr, "bender-cli %s: %s\n%s", this->Command.c_str(), Describe(e).c_str(), this->Usage);
      return 2;
    }
    if (this->Help)
    {
      std::fputs(this->Usage, stdout);
      return 0;
    }
    return -1;
  }

  /// Prints a usage error (exit 2).
  int UsageError(const std::string& problem) const
  {
    std::fprintf(
      stderr, "bender-cli %s: %s\n%s", this->Command.c_str(), problem.c_str(), this->Usage);
    return 2;
  }

private:
  static std::string Describe(const CLI::ParseError& e)
  {
    std::string what = e.what();
    // "The following arguments were not expected: --x" reads as one line already.
    while (!what.empty() && (what.back() == '\n' || what.back() == ' '))
    {
      what.pop_back();
    }
    return what;
  }

  std::string Command;
  const char* Usage;
  bool Help = false;
};

} // namespace bender

#endif
