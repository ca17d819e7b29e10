#include "LogicTestUtilities.h"

#include "ApplyPlan.h"
#include "BenderSession.h"
#include "CfdVerificationTubes.h"
#include "PolyDataCopy.h"
#include "Ribbon.h"

#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

namespace bender
{
namespace test
{

vtkSmartPointer<vtkPolyData> MakeTube(double x0, double x1, double radius, int rings, int sides)
{
  return SweepOpenTube(StraightCentreline(x0, x1, rings - 1), radius, sides);
}

RibbonSpec StraightRibbon(double a, double b)
{
  RibbonSpec ribbon;
  ribbon.start.position = { a, 0, 0 };
  ribbon.end.position = { b, 0, 0 };
  ribbon.start.tangent = ribbon.end.tangent = { 1, 0, 0 };
  ribbon.start.normal = ribbon.end.normal = { 0, 0, 1 };
  return ribbon;
}

RibbonSpec Bent(const RibbonSpec& straight, double degrees)
{
  const double a = degrees * 3.14159265358979323846 / 180.0;
  RibbonSpec bent = straight;
  const Vec3 arm = straight.end.position - straight.start.position;
  bent.end.position = straight.start.position + Rotate({ 0, 0, 1 }, a, arm);
  bent.end.tangent = Rotate({ 0, 0, 1 }, a, straight.end.tangent);
  return bent;
}

WarpSpec Swing(double from, double to, double degrees, double radius)
{
  WarpSpec warp;
  warp.initial = StraightRibbon(from, to);
  warp.final = Bent(warp.initial, degrees);
  warp.radius = radius;
  return warp;
}

FlowStudyInput PreparedThenBentTube(double degrees)
{
  const vtkSmartPointer<vtkPolyData> tube = MakeTube(-20, 20, 5, 41, 32);
  BenderSession session;
  CfdStep step;
  step.clip = false;
  step.inletExtension = 2.0;
  step.outletExtension = 1.0;
  FlowStudyInput input;
  if (!session.SetSurface(tube, "tube") ||
    !session.CommitCfdStep(step, ApplyCfdStep(tube, step).surface, false) ||
    (degrees != 0.0 && !session.ApplyWarp(Swing(0, 15, degrees, 8))))
  {
    return input; // no shapes: the test fails on them
  }
  input.first = tube;
  input.plan = session.GetPlan();
  input.current = DeepCopyOf(session.GetSurface());
  input.name = "tube";
  return input;
}

double MaxDifference(vtkPolyData* a, vtkPolyData* b)
{
  if (!a || !b || a->GetNumberOfPoints() != b->GetNumberOfPoints())
  {
    return std::numeric_limits<double>::infinity();
  }
  double worst = 0.0;
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    a->GetPoint(i, p);
    b->GetPoint(i, q);
    for (int c = 0; c < 3; ++c)
    {
      worst = std::max(worst, std::abs(p[c] - q[c]));
    }
  }
  return worst;
}

double DistanceToWire(const RibbonSpec& ribbon, const Vec3& p)
{
  const Ribbon wire(ribbon);
  double best = std::numeric_limits<double>::infinity();
  const int samples = 4000;
  for (int i = 0; i <= samples; ++i)
  {
    best = std::min(best, Distance(p, wire.Wire().PointAt(double(i) / samples)));
  }
  return best;
}

std::string TemporaryFolder(const std::string& name)
{
  const auto folder = std::filesystem::temp_directory_path() / ("bender-logic-" + name);
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder.string();
}

} // namespace test
} // namespace bender
