#include "FastrakEncoding.h"

#include "TrackingErrors.h"

#include <cstdio>
#include <cstring>
#include <string>

namespace bender
{

std::vector<std::uint8_t> EncodeFastrakRecord(const TrackerPose& pose, FastrakFormat format)
{
  if (pose.station < 1 || pose.station > 4)
  {
    throw TrackingConfigurationError(
      "Fastrak record: station " + std::to_string(pose.station) + " is outside 1..4");
  }
  const double cm[3] = { pose.position.x / 10.0, pose.position.y / 10.0, pose.position.z / 10.0 };
  const double q[4] = {
    pose.orientation.w, pose.orientation.x, pose.orientation.y, pose.orientation.z
  };
  std::vector<std::uint8_t> out = {
    '0', std::uint8_t('0' + pose.station), std::uint8_t(pose.status)
  };
  if (format == FastrakFormat::Binary)
  {
    for (int i = 0; i < 7; ++i)
    {
      const float value = float(i < 3 ? cm[i] : q[i - 3]);
      std::uint32_t bits;
      std::memcpy(&bits, &value, sizeof bits);
      for (int b = 0; b < 4; ++b)
      {
        out.push_back(std::uint8_t((bits >> (8 * b)) & 0xFFu));
      }
    }
  }
  else
  {
    char field[32];
    for (int i = 0; i < 7; ++i)
    {
      const int n = i < 3 ? std::snprintf(field, sizeof field, "%7.2f", cm[i])
                          : std::snprintf(field, sizeof field, "%7.4f", q[i - 3]);
      if (n != 7)
      {
        throw TrackingConfigurationError("Fastrak ASCII record: value " +
          std::to_string(i < 3 ? cm[i] : q[i - 3]) + " does not fit its 7-column field");
      }
      out.insert(out.end(), field, field + 7);
    }
  }
  out.push_back(' ');
  out.push_back(pose.button ? '1' : '0');
  out.push_back(' ');
  return out;
}

} // namespace bender
