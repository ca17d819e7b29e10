#include "SessionAutosave.h"

#include "AtomicFile.h"
#include "WarpPlanIO.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

namespace bender
{

namespace
{
std::string Name(const std::string& path)
{
  return std::filesystem::path(path).filename().string();
}
}

void WriteSessionFile(const SessionSnapshot& snapshot, const std::string& path)
{
  nlohmann::ordered_json root;
  root["format"] = "bender-session";
  root["version"] = 1;
  root["source"] = snapshot.sourcePath;
  if (!snapshot.surfaceName.empty())
  {
    root["name"] = snapshot.surfaceName;
  }
  root["frame"] = snapshot.frame;
  try
  {
    root["plan"] = WarpPlanToJson(snapshot.plan, Name(path) + ": plan");
  }
  catch (const WarpPlanError& e)
  {
    throw SessionFileError(e.what());
  }

  const std::filesystem::path target(path);
  std::error_code ec;
  if (target.has_parent_path())
  {
    std::filesystem::create_directories(target.parent_path(), ec);
  }
  // The project's atomic write: a unique temporary file, flushed to disk, then renamed, so a
  // crash or a second instance never leaves a truncated session file.
  const std::string text = root.dump(2) + "\n";
  std::string problem;
  const bool written = AtomicWriteText(path, text, problem);
  if (!written)
  {
    throw SessionFileError(Name(path) + ": " + problem);
  }
}

SessionSnapshot ReadSessionFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    throw SessionFileError(Name(path) + ": cannot be opened for reading");
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  nlohmann::ordered_json root;
  try
  {
    // Nesting deeper than any session needs is refused before it can exhaust the stack.
    root = nlohmann::ordered_json::parse(buffer.str(),
      [](int depth, nlohmann::ordered_json::parse_event_t, nlohmann::ordered_json&)
      {
        if (depth > 128)
        {
          throw SessionFileError("JSON nested more than 128 levels deep");
        }
        return true;
      });
  }
  catch (const SessionFileError& e)
  {
    throw SessionFileError(Name(path) + ": " + e.what());
  }
  catch (const nlohmann::json::exception& e)
  {
    throw SessionFileError(Name(path) + ": not valid JSON (" + e.what() + ")");
  }
  if (!root.is_object() || root.value("format", std::string()) != "bender-session")
  {
    throw SessionFileError(Name(path) + ": format: not a bender-session file");
  }
  if (!root.contains("version") || !root["version"].is_number_integer() || root["version"] != 1)
  {
    throw SessionFileError(Name(path) + ": version: unknown session file version");
  }
  if (!root.contains("source") || !root["source"].is_string())
  {
    throw SessionFileError(Name(path) + ": source: missing or not a string");
  }
  if (!root.contains("plan") || !root["plan"].is_object())
  {
    throw SessionFileError(Name(path) + ": plan: missing or not an object");
  }
  SessionSnapshot snapshot;
  snapshot.sourcePath = root["source"].get<std::string>();
  snapshot.frame = root.value("frame", std::string("LPS"));
  if (root.contains("name"))
  {
    if (!root["name"].is_string())
    {
      throw SessionFileError(Name(path) + ": name: not a string");
    }
    snapshot.surfaceName = root["name"].get<std::string>();
  }
  try
  {
    snapshot.plan = WarpPlanFromJson(root["plan"], Name(path) + ": plan");
  }
  catch (const WarpPlanError& e)
  {
    throw SessionFileError(e.what());
  }
  return snapshot;
}

} // namespace bender
