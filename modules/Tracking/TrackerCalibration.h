#ifndef bender_TrackerCalibration_h
#define bender_TrackerCalibration_h

#include "Quaternion.h"
#include "Vec3.h"

#include <array>

namespace bender
{

/// Maps tracker space (the Fastrak transmitter frame, mm) to model space (the frame of the
/// mesh, LPS mm):  model = R * (s * tracker) + t  for points, and R * q for orientations.
///
/// R is a rotation (a rigid alignment), t a translation in model mm, s the motion scale
/// (s = 2: 1 mm of hand motion moves the ribbon 2 mm; orientations are not scaled). The
/// clutch of TwoHandRibbonInput re-anchors t with Translate().
class TrackerCalibration
{
public:
  /// Identity: model space = tracker space.
  TrackerCalibration() = default;
  /// Throws TrackingConfigurationError when the rotation is zero or not finite, the
  /// translation is not finite or the scale is not in (0, 1000].
  TrackerCalibration(const Quaternion& rotation, const Vec3& translationMm, double motionScale);

  /// The rigid alignment (with scale `motionScale`) that takes three tracker-space points
  /// (e.g. landmarks touched with the stylus) onto the same three model-space points: the
  /// first point maps exactly, the direction to the second exactly, the plane of the three
  /// as closely as a rotation can. Throws TrackingConfigurationError for (near) collinear
  /// points.
  static TrackerCalibration FromThreePoints(const std::array<Vec3, 3>& tracker,
    const std::array<Vec3, 3>& model,
    double motionScale = 1.0);

  Vec3 MapPoint(const Vec3& trackerMm) const;
  Vec3 MapDirection(const Vec3& trackerDirection) const;
  Quaternion MapOrientation(const Quaternion& tracker) const;

  /// Moves the model-space translation by `modelOffsetMm`.
  void Translate(const Vec3& modelOffsetMm) { this->TranslationMm += modelOffsetMm; }

  const Quaternion& Rotation() const { return this->RotationQ; }
  const Vec3& Translation() const { return this->TranslationMm; }
  double MotionScale() const { return this->Scale; }

private:
  Quaternion RotationQ;
  Vec3 TranslationMm;
  double Scale = 1.0;
};

} // namespace bender

#endif
