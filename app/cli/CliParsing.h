#ifndef bender_CliParsing_h
#define bender_CliParsing_h

// What every bender-cli command shares to read its arguments with CLI11: the application (help
// layout, -h/--help), the checks of numbers, choices and points, and the one function that
// parses and runs (RunCli). The messages follow one rule: a usage error is one line
// "bender-cli <command>: <problem> (see bender-cli <command> --help)" on stderr and exit 2;
// --help prints the command's generated help on stdout and exits 0.

#include <CLI/CLI.hpp>

#include <array>
#include <functional>
#include <iosfwd>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace bender
{

/// The `bender-cli` application with the house help layout (CliHelpFormatter) and -h/--help;
/// the commands add themselves to it as subcommands (CliCommand.h).
std::unique_ptr<CLI::App> NewCliApp();

/// Adds `bender-cli NAME` to `cli`: `summary` is one line (the tool's list of commands, the head
/// of the command's help), `details` the footer of its help (what it does, formats, exit status);
/// `run` is called after a successful parse and returns the exit status (0 success, 1 bad input
/// or failure, 2 usage error). An exception escaping `run` is reported by RunCli in one line.
CLI::App* AddCommand(CLI::App& cli,
  const std::string& name,
  const std::string& summary,
  const std::string& details,
  std::function<int()> run);

/// Parses `args` (the words after `bender-cli`, a command's name first) and runs the command
/// chosen (AddCommand). Returns the exit status: 0 after --help (the help of the command
/// asked, on `out`), 2 after a usage error (one line on `err`; the whole help on `err` when no
/// command is given), the command's status else. Never throws: an exception escaping a command
/// becomes one line "bender-cli <command>: <what>" and exit 1.
int RunCli(CLI::App& cli,
  const std::vector<std::string>& args,
  std::ostream& out,
  std::ostream& err);

/// Runs the one command `name` with RunCli (the in-process entry points that the tests call
/// with their own streams): `add` adds it to a fresh application; `args` are the words after
/// its name.
int RunAlone(const std::string& name,
  const std::vector<std::string>& args,
  std::ostream& out,
  std::ostream& err,
  const std::function<void(CLI::App&)>& add);

/// The longest error line bender-cli prints (a longer message is cut).
constexpr std::size_t MaxErrorLine = 2000;

/// message as the one line bender-cli prints for an error: newlines as spaces, at most
/// MaxErrorLine bytes. Every error path of the command line goes through it.
std::string ErrorLine(const std::string& message);

/// A command's failure: prints "bender-cli <command>: <message>" on stderr and returns 1.
int CommandError(const std::string& command, const std::string& message);

/// A usage error found after parsing (two options that contradict each other, an output of the
/// wrong kind): prints the one line for `command` on `err` and returns 2.
int UsageError(std::ostream& err, const std::string& command, const std::string& problem);

/// CLI11 checks of a number option's text, with the message "'1.5' is not in [0, 1]": a finite
/// number in [min, max]; a whole number in [min, max]; a finite number > min and <= max.
CLI::Validator NumberIn(double min, double max);
CLI::Validator IntegerIn(double min, double max);
CLI::Validator NumberAbove(double min, double max = std::numeric_limits<double>::max());

/// Adds `name` (such as "--seeds") to `command`: points "x,y,z" (three finite numbers, mm),
/// repeatable, and several after one `name` (SplitPointLists); their text goes to `texts`,
/// checked by CLI11. Convert them with Points after parsing.
CLI::Option* AddPointsOption(CLI::App& command,
  const std::string& name,
  std::vector<std::string>& texts,
  const std::string& description);

/// The points of `texts` as checked by AddPointsOption.
std::vector<std::array<double, 3>> Points(const std::vector<std::string>& texts);

/// The endpoints of a vessel given with --seeds (AddPointsOption), the inlet first: none (they
/// are then found automatically) or at least two; one is a usage error (throws
/// CLI::ValidationError, which RunCli reports as such).
std::vector<std::array<double, 3>> EndpointSeeds(const std::vector<std::string>& texts);

/// `option` takes one of `names` (in any case; the value becomes the name as listed here); its
/// help shows them as a|b|c.
CLI::Option* OneOf(CLI::Option* option, const std::vector<std::string>& names);

/// The words with "--seed P1 P2 ..." (and --seeds) turned into "--seed=P1 --seed=P2 ...": a
/// list of points runs up to the first word that is not a point, so that the word after the
/// points stays positional and a negative coordinate is never taken for an option.
std::vector<std::string> SplitPointLists(const std::vector<std::string>& args);

} // namespace bender

#endif
