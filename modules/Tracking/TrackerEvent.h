#ifndef bender_TrackerEvent_h
#define bender_TrackerEvent_h

#include <string>

namespace bender
{

enum class TrackerEventType
{
  Grab,         ///< the stylus button of `station` went down
  Release,      ///< the stylus button of `station` went up
  Disconnected, ///< the device went away mid-stream (unplugged, powered off); Open() again
  ReadError,    ///< another read error ended the stream; `message` says which
  EndOfStream   ///< a replay or a timed simulation reached its end
};

/// Something that happened on a device, in the order it happened.
struct TrackerEvent
{
  TrackerEventType type = TrackerEventType::Grab;
  int station = 0;     ///< 1..4 for Grab/Release, 0 otherwise
  double time = 0.0;   ///< seconds, same time base as TrackerPose::time
  std::string message; ///< one line, for Disconnected/ReadError
};

/// "grab", "release", "disconnected", "read-error", "end-of-stream".
inline const char* ToString(TrackerEventType type)
{
  switch (type)
  {
    case TrackerEventType::Grab:
      return "grab";
    case TrackerEventType::Release:
      return "release";
    case TrackerEventType::Disconnected:
      return "disconnected";
    case TrackerEventType::ReadError:
      return "read-error";
    case TrackerEventType::EndOfStream:
      return "end-of-stream";
  }
  return "unknown";
}

} // namespace bender

#endif
