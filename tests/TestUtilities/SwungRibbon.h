#ifndef bender_SwungRibbon_h
#define bender_SwungRibbon_h

// A ribbon whose end is swung about the start's normal, around the start: the bend the window
// tests and the history benchmark make without a hand.

#include "Vec3.h"
#include "WarpPlan.h"

namespace bendertest
{

/// `ribbon` with its end swung by `degrees` about the start's normal, around the start (the end
/// frame turned with it).
inline bender::RibbonSpec Swung(const bender::RibbonSpec& ribbon, double degrees)
{
  const double a = degrees * 3.14159265358979323846 / 180.0;
  const bender::Vec3 axis = bender::Normalized(ribbon.start.normal);
  bender::RibbonSpec swung = ribbon;
  swung.end.position =
    ribbon.start.position + bender::Rotate(axis, a, ribbon.end.position - ribbon.start.position);
  swung.end.tangent = bender::Rotate(axis, a, ribbon.end.tangent);
  swung.end.normal = bender::Rotate(axis, a, ribbon.end.normal);
  return swung;
}

} // namespace bendertest

#endif
