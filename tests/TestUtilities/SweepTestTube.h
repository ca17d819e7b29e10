#ifndef bender_SweepTestTube_h
#define bender_SweepTestTube_h

// The tube of the sweep tests (issue 24: tests/cfd/SweepCfdTest, the slurm test through
// tests/slurm/WriteSweepTube): an open tube of radius 3 mm along +x from x = -30 to 40 mm, 71
// rings of 24 points (3,360 triangles), made by the one tube generator (CfdVerificationTubes.h).
// tests/data/sweep/bend90.bender.json bends its last 40 mm; its open ends are clipped and
// capped by the sweep's Prepare for CFD step (the end at x = -30 is the inlet).

#include "CfdVerificationTubes.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

namespace bendertest
{

inline vtkSmartPointer<vtkPolyData> SweepTestTube()
{
  return bender::SweepOpenTube(bender::StraightCentreline(-30.0, 40.0, 70), 3.0, 24);
}

} // namespace bendertest

#endif
