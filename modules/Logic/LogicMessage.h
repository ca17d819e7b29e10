#ifndef bender_LogicMessage_h
#define bender_LogicMessage_h

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

inline const char* ToString(MessageSeverity severity)
{
  switch (severity)
  {
    case MessageSeverity::Info:
      return "info";
    case MessageSeverity::Warning:
      return "warning";
    case MessageSeverity::Error:
      return "error";
  }
  return "info";
}

} // namespace bender

#endif
