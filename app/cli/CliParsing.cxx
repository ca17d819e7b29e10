#include "CliParsing.h"

#include "BenderErrors.h"
#include "CliHelpFormatter.h"
#include "VesselWorkflows.h"
#include "VtkMessageGuard.h"

#include <vtkLogger.h>
#include <vtkOutputWindow.h>

#include <cmath>
#include <cstdio>
#include <new>
#include <ostream>

namespace bender
{
namespace
{
std::string Number(double value)
{
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

bool IsPoint(const std::string& text)
{
  try
  {
    ParsePoint(text, "");
    return true;
  }
  catch (const InputError&)
  {
    return false;
  }
}

// The command whose arguments were being read ("" for the tool itself).
std::string CommandOf(const CLI::App& cli)
{
  const std::vector<CLI::App*> chosen = cli.get_subcommands();
  return chosen.empty() ? std::string() : chosen.front()->get_name();
}

std::string Prefix(const std::string& command)
{
  return command.empty() ? "bender-cli" : "bender-cli " + command;
}

// Checks that `text` is a finite number, and a whole one when asked; the message otherwise.
std::string NumberProblem(const std::string& text, double& value, bool integer)
{
  std::size_t used = 0;
  try
  {
    value = std::stod(text, &used);
  }
  catch (const std::exception&)
  {
    used = 0;
  }
  if (text.empty() || used != text.size() || !std::isfinite(value))
  {
    return "'" + text + "' is not a number";
  }
  if (integer && value != std::floor(value))
  {
    return "'" + text + "' is not a whole number";
  }
  return {};
}

CLI::Validator Interval(double min, double max, bool openMin, bool integer)
{
  const std::string range = (openMin ? "(" : "[") + Number(min) + ", " +
    (max == std::numeric_limits<double>::max() ? "inf)" : Number(max) + "]");
  return CLI::Validator(
    [=](std::string& text) -> std::string
    {
      double value = 0.0;
      if (std::string problem = NumberProblem(text, value, integer); !problem.empty())
      {
        return problem;
      }
      if (value < min || (openMin && value == min) || value > max)
      {
        return "'" + text + "' is not in " + range;
      }
      return {};
    },
    range);
}
} // namespace

std::unique_ptr<CLI::App> NewCliApp()
{
  auto cli = std::make_unique<CLI::App>(
    "Bender: bend vessel surfaces with the ribbon warp, for surgery planning and CFD.",
    "bender-cli");
  cli->formatter(std::make_shared<CliHelpFormatter>());
  cli->option_defaults()->group("options");
  cli->set_help_flag("-h,--help", "this help");
  return cli;
}

int RunCli(CLI::App& cli,
  const std::vector<std::string>& args,
  std::ostream& out,
  std::ostream& err)
{
  const std::vector<std::string> words = SplitPointLists(args);
  try
  {
    // CLI11 consumes its argument vector from the back.
    std::vector<std::string> reversed(words.rbegin(), words.rend());
    cli.parse(reversed);
    return 0;
  }
  catch (const CLI::CallForHelp&)
  {
    out << cli.help();
    return 0;
  }
  catch (const CLI::Success&)
  {
    return 0;
  }
  catch (const CLI::RuntimeError& e)
  {
    return e.get_exit_code(); // the command has said why
  }
  catch (const CLI::ParseError& e)
  {
    const std::string command = CommandOf(cli);
    if (command.empty() && args.empty())
    {
      err << cli.help();
      return 2;
    }
    std::string problem = e.what();
    const CLI::App* reading = command.empty() ? &cli : cli.get_subcommands().front();
    if (command.empty() && !args.front().empty() && args.front()[0] != '-')
    {
      problem = "unknown command '" + args.front() + "'";
    }
    else if (!reading->remaining().empty())
    {
      // A word the command does not know explains the rest (CLI11 checks the required
      // arguments first).
      const std::string word = reading->remaining().front();
      problem = (word.size() > 1 && word[0] == '-' ? "unknown option '" : "unexpected argument '") +
        word + "'";
    }
    return UsageError(err, command, problem);
  }
  // What escapes a command (such as running out of memory on an absurd parameter) becomes one
  // line, so that the tool never aborts.
  catch (const std::bad_alloc&)
  {
    err << Prefix(CommandOf(cli))
        << ": out of memory (check the parameters: a tolerance or size too small or too "
           "large?)\n";
  }
  catch (const std::exception& e)
  {
    err << Prefix(CommandOf(cli)) << ": " << ErrorLine(e.what()) << "\n";
  }
  std::fflush(stdout);
  return 1;
}

CLI::App* AddCommand(CLI::App& cli,
  const std::string& name,
  const std::string& summary,
  const std::string& details,
  std::function<int()> run)
{
  CLI::App* command = cli.add_subcommand(name, summary);
  command->footer(details);
  if (CLI::Option* help = command->get_help_ptr())
  {
    help->group("options");
  }
  command->callback(
    [run = std::move(run)]
    {
      // VTK's own messages would repeat ours; every failure is reported in one line. VTK
      // writes them twice: through the output window, and through its logger (loguru), which
      // also prints the executive's multi-line "returned failure for request" report.
      vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
      vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
      if (const int status = run())
      {
        throw CLI::RuntimeError(status); // RunCli returns it
      }
    });
  return command;
}

int RunAlone(const std::string& name,
  const std::vector<std::string>& args,
  std::ostream& out,
  std::ostream& err,
  const std::function<void(CLI::App&)>& add)
{
  const std::unique_ptr<CLI::App> cli = NewCliApp();
  add(*cli);
  std::vector<std::string> words = { name };
  words.insert(words.end(), args.begin(), args.end());
  return RunCli(*cli, words, out, err);
}

int CommandError(const std::string& command, const std::string& message)
{
  std::fprintf(stderr, "bender-cli %s: %s\n", command.c_str(), ErrorLine(message).c_str());
  return 1;
}

std::string ErrorLine(const std::string& message)
{
  return io_detail::OneLine(message, MaxErrorLine);
}

int UsageError(std::ostream& err, const std::string& command, const std::string& problem)
{
  std::string line = ErrorLine(problem);
  while (!line.empty() && (line.back() == '\n' || line.back() == ' '))
  {
    line.pop_back();
  }
  err << Prefix(command) << ": " << line << " (see " << Prefix(command) << " --help)\n";
  return 2;
}

CLI::Validator NumberIn(double min, double max)
{
  return Interval(min, max, false, false);
}

CLI::Validator IntegerIn(double min, double max)
{
  return Interval(min, max, false, true);
}

CLI::Validator NumberAbove(double min, double max)
{
  return Interval(min, max, true, false);
}

CLI::Option* AddPointsOption(CLI::App& command,
  const std::string& name,
  std::vector<std::string>& texts,
  const std::string& description)
{
  return command.add_option(name, texts, description)
    ->allow_extra_args(false)
    ->type_name("x,y,z ...")
    ->check(CLI::Validator([](std::string& text) -> std::string
      { return IsPoint(text) ? std::string() : "'" + text + "' is not x,y,z (three numbers)"; },
      "x,y,z"));
}

std::vector<std::array<double, 3>> Points(const std::vector<std::string>& texts)
{
  std::vector<std::array<double, 3>> points;
  for (const std::string& text : texts)
  {
    points.push_back(ParsePoint(text, "point"));
  }
  return points;
}

CLI::Option* OneOf(CLI::Option* option, const std::vector<std::string>& names)
{
  std::string shown;
  for (const std::string& name : names)
  {
    shown += (shown.empty() ? "" : "|") + name;
  }
  return option->transform(CLI::IsMember(names, CLI::ignore_case))->type_name(shown);
}

std::vector<std::array<double, 3>> EndpointSeeds(const std::vector<std::string>& texts)
{
  if (texts.size() == 1)
  {
    throw CLI::ValidationError("--seeds", "give at least two points (the inlet first)");
  }
  return Points(texts);
}

std::vector<std::string> SplitPointLists(const std::vector<std::string>& args)
{
  std::vector<std::string> words;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    if ((args[i] != "--seed" && args[i] != "--seeds") || i + 1 >= args.size())
    {
      words.push_back(args[i]);
      continue;
    }
    const std::string option = args[i];
    words.push_back(option + "=" + args[++i]);
    while (i + 1 < args.size() && IsPoint(args[i + 1]))
    {
      words.push_back(option + "=" + args[++i]);
    }
  }
  return words;
}

} // namespace bender
