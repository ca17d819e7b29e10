// PrepareForCfd never drops a vessel end (issue 23): a tube with a side branch 1.2 mm wide,
// open or closed at the branch's tip, gets its three ends; an end the centerlines miss is
// refused in one line naming its position and what to do (--end, --no-clip), and clipped when
// --end gives it; a --end point off the vessel of the nearest end is refused, not cut elsewhere.
// The plan's step of a prepared surface made through a --end replays to the same ends.

#include "ApplyPlan.h"
#include "BenderErrors.h"
#include "PrepareForCfd.h"
#include "VesselCenterlines.h"
#include "VesselTestUtilities.h"

#include <gtest/gtest.h>

#include <vtkOutputWindow.h>
#include <vtkPolyData.h>

#include <cmath>

using namespace bender;

namespace
{
/// A tube of radius 3 along z, open at z = +-20, with a branch 1.2 mm wide along +x that ends
/// at x = `tip`: open there when the grid stops before it (x = 20), else rounded and closed.
vtkSmartPointer<vtkPolyData> BranchedTube(double tip)
{
  // Radii off the grid's nodes: no iso-surface vertex lands twice on one node.
  const std::vector<test::Segment> tubes = { { { { 0, 0, -40 } }, { { 0, 0, 40 } }, 3.013 },
    { { { 0, 0, 0 } }, { { tip, 0, 0 } }, 0.6013 } };
  const double bounds[6] = { -5, 20, -4.2, 4.2, -20, 20 };
  return test::ImplicitTubes(tubes, bounds, 0.2);
}

/// The thin ends (radius below 1 mm) of a result.
int ThinEnds(const PrepareForCfdResult& r)
{
  int thin = 0;
  for (const CfdEnd& end : r.ends)
  {
    thin += end.radius < 1.0 ? 1 : 0;
  }
  return thin;
}

/// The X of "... is X mm from the vessel ..." in a refusal.
double MillimetresFrom(const std::string& what)
{
  const std::size_t at = what.find(" mm from the vessel");
  return at == std::string::npos ? -1.0 : std::stod(what.substr(what.rfind(" is ", at) + 4));
}

/// The one-line InputError of PrepareForCfd(surface, options); "" when it succeeds.
std::string Refusal(vtkPolyData* surface, const PrepareForCfdOptions& options)
{
  try
  {
    PrepareForCfd(surface, options);
  }
  catch (const InputError& e)
  {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_EQ(what.rfind(options.inputName + ": ", 0), 0u) << what;
    return what;
  }
  return {};
}

class PrepareForCfdEndsTest : public ::testing::Test
{
protected:
  void SetUp() override { vtkOutputWindow::GetInstance()->SetDisplayModeToNever(); }
};
} // namespace

TEST_F(PrepareForCfdEndsTest, AnOpenEndNoCenterlineReachesIsRefusedWithWhatToDo)
{
  const vtkSmartPointer<vtkPolyData> surface = BranchedTube(40.0);
  PrepareForCfdOptions options;
  options.inputName = "branched.vtp";
  // Centerlines of the trunk only (as a user's --centerlines may be).
  CenterlineOptions trunk;
  trunk.seeds = { { { 0, 0, -20 } }, { { 0, 0, 20 } } };
  options.centerlines = ComputeCenterlines(surface, trunk).paths;
  const std::string what = Refusal(surface, options);
  EXPECT_NE(
    what.find("the open end at (20, 0, 0) (1.2 mm wide) would not be clipped"), std::string::npos)
    << what;
  EXPECT_NE(what.find("give centerlines through it"), std::string::npos) << what;
  EXPECT_NE(what.find("--no-clip"), std::string::npos) << what;
  // A --end at the branch's tip with those centerlines: its nearest end is the trunk's, whose
  // wall is 16.5 mm away; refused, the trunk is not cut there.
  options.ends.push_back({ { { 19.5, 0, 0 } }, 2.0 });
  const std::string far = Refusal(surface, options);
  EXPECT_NE(far.find("mm from the vessel of the nearest end"), std::string::npos) << far;
  EXPECT_NEAR(MillimetresFrom(far), 19.5 - 3.0, 0.3) << far;
  // Computed centerlines reach it: three ends.
  PrepareForCfdOptions computed;
  computed.inputName = "branched.vtp";
  const PrepareForCfdResult r = PrepareForCfd(surface, computed);
  EXPECT_EQ(r.ends.size(), 3u);
  EXPECT_EQ(ThinEnds(r), 1);
}

TEST_F(PrepareForCfdEndsTest, ABlindBranchIsClippedAtTheEndGivenAndTheStepReplays)
{
  // The branch ends closed inside the grid, 9 mm from the axis: the centerlines of an open
  // surface start at its open ends only, so without --end the branch is not an end.
  const vtkSmartPointer<vtkPolyData> surface = BranchedTube(9.0);
  PrepareForCfdOptions options;
  options.inputName = "blind.vtp";
  options.ends.push_back({ { { 9.5, 0, 0 } }, -1.0 });
  const PrepareForCfdResult r = PrepareForCfd(surface, options);
  ASSERT_EQ(r.ends.size(), 3u);
  ASSERT_EQ(ThinEnds(r), 1);
  for (const CfdEnd& end : r.ends)
  {
    EXPECT_GE(end.clipDistance, 0.0);
    if (end.radius < 1.0)
    {
      EXPECT_GT(end.normal[0], std::cos(10.0 * M_PI / 180.0));
      EXPECT_GT(end.clipCentre[0], 4.0);
      EXPECT_LT(end.clipCentre[0], 9.5);
    }
  }
  // The plan keeps every end's cut: replayed, the same three ends at the same places.
  const CfdStep step = ResolvedCfdStep(CfdStepOf(options, 0), r);
  const PrepareForCfdResult again = ApplyCfdStep(surface, step);
  ASSERT_EQ(again.ends.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k)
  {
    EXPECT_EQ(again.ends[k].name, r.ends[k].name);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_NEAR(again.ends[k].clipCentre[a], r.ends[k].clipCentre[a], 0.05 * r.ends[k].radius);
    }
  }
}
