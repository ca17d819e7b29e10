// bender-cli formats [--json]: the mesh formats Bender reads and writes, as the one table of
// modules/IO/MeshFormats.h holds them (a registered format is listed, and written by export).

#include "CliCommand.h"
#include "CliParsing.h"

#include "MeshFormats.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

namespace
{
const char* const Details =
  "Lists the surface mesh formats: their name, extensions, whether Bender reads and writes "
  "them, and what file dialogs call them. Every format marked writable is written by `bender-cli "
  "export` and `bender-cli warp`, chosen by "
  "the output's extension.\n"
  "\n"
  "exit status: 0";

std::string Join(const std::vector<std::string>& words, const char* separator)
{
  std::string joined;
  for (const std::string& word : words)
  {
    joined += (joined.empty() ? "" : separator) + word;
  }
  return joined;
}

int RunFormats(bool json)
{
  const std::vector<bender::MeshFormat> formats = bender::MeshFormats();
  if (json)
  {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const bender::MeshFormat& format : formats)
    {
      list.push_back({ { "name", format.name },
        { "extensions", format.extensions },
        { "read", format.CanRead() },
        { "write", format.CanWrite() } });
    }
    std::printf("%s\n", nlohmann::ordered_json{ { "formats", list } }.dump(2).c_str());
    return 0;
  }
  std::size_t extensionWidth = std::string("extensions").size();
  for (const bender::MeshFormat& format : formats)
  {
    extensionWidth = std::max(extensionWidth, Join(format.extensions, " ").size());
  }
  const int width = static_cast<int>(extensionWidth);
  std::printf("%-8s %-*s %-5s %-5s %s\n", "name", width, "extensions", "read", "write", "label");
  for (const bender::MeshFormat& format : formats)
  {
    std::printf("%-8s %-*s %-5s %-5s %s\n",
      format.name.c_str(),
      width,
      Join(format.extensions, " ").c_str(),
      format.CanRead() ? "yes" : "-",
      format.CanWrite() ? "yes" : "-",
      format.label.c_str());
  }
  return 0;
}
} // namespace

void bender::AddFormatsCommand(CLI::App& cli)
{
  auto json = std::make_shared<bool>(false);
  CLI::App* formats = AddCommand(cli,
    "formats",
    "list the mesh formats Bender reads and writes",
    Details,
    [json] { return RunFormats(*json); });
  formats->add_flag("--json",
    *json,
    "print {\"formats\": [{\"name\", \"extensions\", \"read\", \"write\"}]} instead of a table");
}
