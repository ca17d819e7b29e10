#ifndef bender_ThinBranchTube_h
#define bender_ThinBranchTube_h

// The clip tests' tube (bender_cfd_clip_tests): a trunk 6 mm wide along z with a side branch
// 1.2 mm wide along +x, prepared for CFD with short extensions (three ends). A single cell size
// set by the trunk loses the branch's end; the graded mesh keeps it.

#include "PrepareForCfd.h"
#include "VesselTestUtilities.h"

#include <vector>

namespace bender
{
namespace test
{

inline PrepareForCfdResult PreparedThinBranchTube()
{
  // Radii off the grid's nodes: no iso-surface vertex lands twice on one node.
  const std::vector<Segment> tubes = { { { { 0, 0, -40 } }, { { 0, 0, 40 } }, 3.013 },
    { { { 0, 0, 0 } }, { { 40, 0, 0 } }, 0.6013 } };
  const double bounds[6] = { -5, 20, -4.2, 4.2, -20, 20 };
  PrepareForCfdOptions prepare;
  prepare.inletExtension = 2.0;
  prepare.outletExtension = 2.0;
  return PrepareForCfd(ImplicitTubes(tubes, bounds, 0.2), prepare);
}

} // namespace test
} // namespace bender

#endif
