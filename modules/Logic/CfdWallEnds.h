#ifndef bender_CfdWallEnds_h
#define bender_CfdWallEnds_h

// Vessel ends left labelled as wall (issue 23, "the case refuses to run with an end missing"):
// a cap that should be an inlet or an outlet but carries the wall's label would close that
// vessel in the case, and the flow would silently go elsewhere. Found on the surface before
// anything is written (cfd-case with or without --run): a flat, disc-like part of the wall as
// wide as a vessel end, whose rim turns sharply into the vessel's wall, as every cap does.

#include "LabelledSurface.h"

#include <array>
#include <string>
#include <vector>

namespace bender
{

/// A flat part of the wall shaped like a vessel end (the surface's units and frame).
struct CfdWallEnd
{
  std::array<double, 3> centre{}; ///< the area-weighted centre
  std::array<double, 3> normal{}; ///< unit normal, as the triangles face
  double diameter = 0.0;          ///< equivalent diameter 2 sqrt(area / pi)
  long long triangles = 0;
};

/// The flat regions of the wall (its triangles coplanar within 1 degree and a hundred-thousandth
/// of the surface's size) that look like a vessel's cap: at least minDiameter across, at least
/// three triangles, disc-like (4 pi area / perimeter^2 >= 0.5), with a rim where the wall turns
/// by more than 60 degrees on average and along at least half of it. In order of decreasing
/// diameter; empty for a surface without triangles.
std::vector<CfdWallEnd> FindWallEnds(const LabelledSurface& surface, double minDiameter);

/// Throws InputError, one line naming `name` and the widest end labelled as wall (where and how
/// wide, in mm: the surface is Bender's, LPS millimetres) and what to do, when FindWallEnds
/// finds one at least half as wide as smallestEnd (the narrowest labelled end, mm).
void CheckNoWallEnd(const LabelledSurface& surface, double smallestEnd, const std::string& name);

} // namespace bender

#endif
