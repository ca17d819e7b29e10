#ifndef bender_RibbonLengthChange_h
#define bender_RibbonLengthChange_h

#include "WarpPlan.h"

#include <string>

namespace bender
{

/// A change of the ribbon's length by more than this fraction is worth telling: the warp
/// compresses (or stretches) the vessel along the ribbon by about as much, which no mesh check
/// sees (the surface stays clean while the vessel gets shorter).
constexpr double NotableRibbonLengthChange = 0.10;

/// How a warp changes its ribbon's length: the final wire's length over the initial wire's,
/// minus 1 (-0.2: 20 % shorter). Throws GeometryError for an invalid ribbon.
double RibbonLengthChange(const WarpSpec& warp);

/// One clause for the commit's message when the length changes by more than
/// NotableRibbonLengthChange ("the ribbon is 20 % shorter (19.3 -> 15.4 mm): the vessel is
/// compressed along it"), else empty (also for an invalid ribbon).
std::string RibbonLengthNote(const WarpSpec& warp);

} // namespace bender

#endif
