#include "TrackerCalibration.h"

#include "TrackingErrors.h"

#include <cmath>

namespace bender
{

TrackerCalibration::TrackerCalibration(const Quaternion& rotation,
  const Vec3& translationMm,
  double motionScale)
  : TranslationMm(translationMm)
  , Scale(motionScale)
{
  const double n = std::sqrt(Dot4(rotation, rotation));
  if (!std::isfinite(n) || n < 1e-9)
  {
    throw TrackingConfigurationError("tracker calibration: the rotation quaternion is zero or "
                                     "not finite");
  }
  if (!IsFinite(translationMm))
  {
    throw TrackingConfigurationError("tracker calibration: the translation is not finite");
  }
  if (!(motionScale > 0.0 && motionScale <= 1000.0))
  {
    throw TrackingConfigurationError(
      "tracker calibration: motion scale " + std::to_string(motionScale) + " is not in (0, 1000]");
  }
  this->RotationQ = { rotation.w / n, rotation.x / n, rotation.y / n, rotation.z / n };
}

TrackerCalibration TrackerCalibration::FromThreePoints(const std::array<Vec3, 3>& tracker,
  const std::array<Vec3, 3>& model,
  double motionScale)
{
  // An orthonormal frame on each triangle; R takes the tracker frame onto the model frame.
  const auto frame = [](const std::array<Vec3, 3>& p, const char* which)
  {
    const Vec3 e0 = p[1] - p[0];
    const Vec3 n = Cross(e0, p[2] - p[0]);
    if (!IsFinite(n) || Norm(n) < 1e-6 * Dot(e0, e0) || Norm(e0) < 1e-9)
    {
      throw TrackingConfigurationError(
        std::string("tracker calibration: the three ") + which + " points are collinear");
    }
    const Vec3 a = Normalized(e0);
    const Vec3 c = Normalized(n);
    return std::array<Vec3, 3>{ a, Cross(c, a), c };
  };
  const std::array<Vec3, 3> ft = frame(tracker, "tracker");
  const std::array<Vec3, 3> fm = frame(model, "model");
  // R = Fm * Ft^T, as columns R e_j = sum_i fm_i (ft_i)_j.
  const auto column = [&](int j) { return fm[0] * ft[0][j] + fm[1] * ft[1][j] + fm[2] * ft[2][j]; };
  const Quaternion r = QuaternionFromColumns(column(0), column(1), column(2));
  TrackerCalibration calibration(r, Vec3{}, motionScale);
  calibration.TranslationMm = model[0] - calibration.MapPoint(tracker[0]);
  return calibration;
}

Vec3 TrackerCalibration::MapPoint(const Vec3& trackerMm) const
{
  return RotateByQuaternion(this->RotationQ, trackerMm * this->Scale) + this->TranslationMm;
}

Vec3 TrackerCalibration::MapDirection(const Vec3& trackerDirection) const
{
  return RotateByQuaternion(this->RotationQ, trackerDirection);
}

Quaternion TrackerCalibration::MapOrientation(const Quaternion& tracker) const
{
  return this->RotationQ * tracker;
}

} // namespace bender
