#ifndef bender_TwistUnwrapper_h
#define bender_TwistUnwrapper_h

#include "WarpPlan.h"

namespace bender
{

/// The interactive twist unwrapping of spec convention 4: the final ribbon's total twist is
/// kept continuous between updates by choosing its extraTurns, starting at grab from the
/// initial ribbon's twist. The stored extraTurns make a replay exact.
class TwistUnwrapper
{
public:
  /// Starts at the twist of `initial` (its extraTurns are taken as given).
  /// Throws InvalidRibbonError when `initial` is invalid.
  void Start(const RibbonSpec& initial);

  /// Returns `next` with extraTurns chosen so that its total twist is the closest to the
  /// previous accepted one (|change| <= pi). Does not accept it: call Accept once the warp
  /// was applied. Throws InvalidRibbonError when `next` is invalid.
  RibbonSpec Unwrap(const RibbonSpec& next) const;

  /// Records the total twist of an unwrapped ribbon as the new reference.
  void Accept(const RibbonSpec& unwrapped);

  /// The reference total twist, radians.
  double Twist() const { return this->Reference; }

private:
  double Reference = 0.0;
};

} // namespace bender

#endif
