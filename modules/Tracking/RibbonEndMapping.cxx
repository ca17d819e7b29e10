#include "RibbonEndMapping.h"

#include "TrackingErrors.h"

#include <algorithm>
#include <array>
#include <cmath>
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

RibbonAnchor AnchorHandsToRibbon(const TrackerPose& left,
  const TrackerPose& right,
  const RibbonSpec& ribbon,
  double motionScale,
  const Quaternion& fallback)
{
  if (!(std::isfinite(motionScale) && motionScale >= 0.0 && motionScale <= 1000.0))
  {
    throw TrackingConfigurationError("relative tracking: motion scale " +
      std::to_string(motionScale) + " is not in [0, 1000] (0: automatic)");
  }
  RibbonAnchor anchor;
  anchor.left = left;
  anchor.right = right;
  anchor.ribbon = ribbon;
  anchor.rotation = fallback;
  anchor.scale = motionScale > 0.0 ? motionScale : 1.0;
  const Vec3 hands = right.position - left.position;
  const Vec3 chord = ribbon.end.position - ribbon.start.position;
  const double span = Norm(hands);
  const double length = Norm(chord);
  if (!(span >= 1.0) || !(length > 0.0) || !std::isfinite(span) || !std::isfinite(length))
  {
    return anchor; // hands together (or a point ribbon): no frame to carry, keep the fallback
  }
  // An orthonormal frame (x along the chord, z from the normal) on each side.
  const auto frame = [](const Vec3& along, const Vec3& up) -> std::optional<std::array<Vec3, 3>>
  {
    const Vec3 x = Normalized(along);
    const Vec3 z = up - x * Dot(up, x);
    if (!(Norm(z) > 1e-6))
    {
      return std::nullopt;
    }
    const Vec3 zn = Normalized(z);
    return std::array<Vec3, 3>{ x, Cross(zn, x), zn };
  };
  const auto fh = frame(hands, RotateByQuaternion(left.orientation, { 0, 0, 1 }));
  const auto fr = frame(chord, ribbon.start.normal);
  if (fh && fr)
  {
    // R = Fr * Fh^T, as columns R e_j = sum_i fr_i (fh_i)_j.
    const auto column = [&](int j)
    { return (*fr)[0] * (*fh)[0][j] + (*fr)[1] * (*fh)[1][j] + (*fr)[2] * (*fh)[2][j]; };
    anchor.rotation = QuaternionFromColumns(column(0), column(1), column(2));
  }
  if (motionScale == 0.0)
  {
    anchor.scale = length / span;
  }
  return anchor;
}

RibbonEnd RelativeRibbonEnd(const TrackerPose& pose, Hand hand, const RibbonAnchor& anchor)
{
  const TrackerPose& at = hand == Hand::Left ? anchor.left : anchor.right;
  const RibbonEnd& held = hand == Hand::Left ? anchor.ribbon.start : anchor.ribbon.end;
  const Quaternion turn =
    anchor.rotation * (pose.orientation * Conjugate(at.orientation)) * Conjugate(anchor.rotation);
  RibbonEnd end;
  end.position = held.position +
    RotateByQuaternion(anchor.rotation, (pose.position - at.position) * anchor.scale);
  end.tangent = RotateByQuaternion(turn, held.tangent);
  end.normal = RotateByQuaternion(turn, held.normal);
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
