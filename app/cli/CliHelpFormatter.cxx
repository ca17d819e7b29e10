#include "CliHelpFormatter.h"

#include <sstream>

namespace bender
{
namespace
{
// The value name shown after an option: its option text, else its type name without the
// validators' descriptions that CLI11 appends after a colon ("SPEC", not "SPEC:{...}").
std::string ValueName(const CLI::Option* option)
{
  if (!option->get_option_text().empty())
  {
    return option->get_option_text();
  }
  const std::string name = option->get_type_name();
  return name.substr(0, name.find(':'));
}

bool IsHelp(const CLI::App* app, const CLI::Option* option)
{
  return option == app->get_help_ptr() || option == app->get_help_all_ptr();
}
} // namespace

CliHelpFormatter::CliHelpFormatter()
{
  this->column_width(28);
  this->label("Positionals", "arguments");
}

std::string CliHelpFormatter::Wrap(const std::string& text, std::size_t width, std::size_t indent)
{
  std::string wrapped;
  std::istringstream lines(text);
  std::string line;
  bool first = true;
  while (std::getline(lines, line))
  {
    if (!first)
    {
      wrapped += '\n';
    }
    first = false;
    // A continuation keeps the line's own indentation.
    const std::size_t lead =
      line.find_first_not_of(' ') == std::string::npos ? 0 : line.find_first_not_of(' ') + indent;
    while (line.size() > width)
    {
      std::size_t cut = line.rfind(' ', width);
      if (cut == std::string::npos || cut <= lead)
      {
        break;
      }
      wrapped += line.substr(0, cut) + '\n';
      line = std::string(lead, ' ') + line.substr(cut + 1);
    }
    wrapped += line;
  }
  return wrapped;
}

std::string CliHelpFormatter::make_help(const CLI::App* app,
  std::string name,
  CLI::AppFormatMode mode) const
{
  std::string help = this->make_usage(app, name);
  if (!app->get_description().empty())
  {
    help += "\n" + Wrap(app->get_description(), Width) + "\n";
  }
  help += this->make_positionals(app);
  help += this->make_groups(app, mode);
  help += this->make_subcommands(app, mode);
  if (!app->get_footer().empty())
  {
    help += "\n" + Wrap(app->get_footer(), Width) + "\n";
  }
  return help;
}

std::string CliHelpFormatter::make_usage(const CLI::App* app, std::string name) const
{
  std::string usage = "usage: " + name;
  if (!app->get_subcommands({}).empty())
  {
    return usage + " COMMAND [ARGS...]\n"; // the tool: its options are listed below
  }
  const std::vector<const CLI::Option*> options =
    app->get_options([](const CLI::Option*) { return true; });
  for (const CLI::Option* option : options)
  {
    if (option->nonpositional())
    {
      continue;
    }
    std::string word = option->get_name(true, false);
    if (option->get_expected_max() >= CLI::detail::expected_max_vector_size)
    {
      word += " ...";
    }
    usage += " " + (option->get_required() ? word : "[" + word + "]");
  }
  bool optional = false;
  for (const CLI::Option* option : options)
  {
    if (!option->nonpositional() || IsHelp(app, option))
    {
      continue;
    }
    if (!option->get_required())
    {
      optional = true;
      continue;
    }
    usage += option->get_snames().empty() ? " --" + option->get_lnames().front()
                                          : " -" + option->get_snames().front();
    if (option->get_type_size() != 0)
    {
      usage += " " + ValueName(option);
    }
  }
  return usage + (optional ? " [options]\n" : "\n");
}

std::string CliHelpFormatter::make_option_opts(const CLI::Option* option) const
{
  if (!option->nonpositional() || option->get_type_size() == 0)
  {
    return {}; // a positional's name says it; a flag takes no value
  }
  return " " + ValueName(option);
}

std::string CliHelpFormatter::make_option_desc(const CLI::Option* option) const
{
  std::string description = option->get_description();
  if (!option->get_default_str().empty())
  {
    description += " (default " + option->get_default_str() + ")";
  }
  return Wrap(description, Width - this->column_width_);
}

std::string CliHelpFormatter::make_subcommand(const CLI::App* command) const
{
  std::stringstream out;
  CLI::detail::format_help(out,
    command->get_name(),
    Wrap(command->get_description(), Width - this->column_width_),
    this->column_width_);
  return out.str();
}

} // namespace bender
