#include "RibbonEndMapping.h"

#include "TrackingErrors.h"

#include <algorithm>
#include <sstream>

namespace bender
{

std::optional<Hand> HandMapping::HandOf(int station) const
{
  if (station == this->leftStation)
  {
    return Hand::Left;
  }
  if (station == this->rightStation)
  {
    return Hand::Right;
  }
  return std::nullopt;
}

RibbonEnd RibbonEndFromPose(const TrackerPose& pose,
  Hand hand,
  const TrackerCalibration& calibration)
{
  const Quaternion q = calibration.MapOrientation(pose.orientation);
  const Vec3 x = RotateByQuaternion(q, { 1, 0, 0 });
  RibbonEnd end;
  end.position = calibration.MapPoint(pose.position);
  end.tangent = hand == Hand::Left ? x : -x;
  end.normal = RotateByQuaternion(q, { 0, 0, 1 });
  return end;
}

std::vector<int> ParseStationList(const std::string& text)
{
  std::vector<int> stations;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ','))
  {
    if (item.size() != 1 || item[0] < '1' || item[0] > '4')
    {
      throw TrackingConfigurationError(
        "stations '" + text + "': '" + item + "' is not a station number 1..4");
    }
    const int s = item[0] - '0';
    if (std::find(stations.begin(), stations.end(), s) != stations.end())
    {
      throw TrackingConfigurationError("stations '" + text + "': station " + item + " twice");
    }
    stations.push_back(s);
  }
  if (stations.empty() || text.back() == ',')
  {
    throw TrackingConfigurationError("stations '" + text + "': expected e.g. 1,2");
  }
  return stations;
}

} // namespace bender
