#ifndef bender_LogicMessage_h
#define bender_LogicMessage_h

#include <cstddef>
#include <iterator>
#include <string>

namespace bender
{

enum class MessageSeverity
{
  Info,    ///< something happened as asked ("Loaded aneurysm.stl: 20294 triangles")
  Warning, ///< done, but the user should know (space-inversion risk, a cancelled live warp)
  Error    ///< not done; the text names the input and the problem
};

/// A user-facing message collected by the logic layer and shown by the GUI (status bar, log).
struct LogicMessage
{
  MessageSeverity severity = MessageSeverity::Info;
  std::string text;
};

/// "info", "warning", "error" (in the order of MessageSeverity).
inline const char* ToString(MessageSeverity severity)
{
  constexpr const char* names[] = { "info", "warning", "error" };
  const auto index = static_cast<std::size_t>(severity);
  return index < std::size(names) ? names[index] : names[0];
}

} // namespace bender

#endif
