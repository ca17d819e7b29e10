// The generated tubes of the CFD verification cases (CfdVerificationTubes.h) without OpenFOAM:
// closed, outward, labelled wall / inlet / outlet_1, of the volume of their polygonal section,
// and accepted by WriteOpenFoamCase as any labelled vessel; bender-cli cfd-verify's usage errors.

#include "CfdVerificationTubes.h"
#include "BenderMeshCheck.h"
#include "CfdCase.h"
#include "CfdTestUtilities.h"
#include "PatchLabels.h"

#include "../cli_post/InProcessCli.h"

#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkFieldData.h>

#include <cmath>

namespace
{
constexpr double Pi = 3.14159265358979323846;

// Checks the tube and returns its signed volume (positive when the triangles face outwards).
double ClosedLabelledTubeVolume(vtkPolyData* tube)
{
  bender::MeshCheckOptions options;
  options.selfIntersections = true;
  const bender::MeshCheckReport report = bender::CheckMesh(tube, nullptr, options);
  EXPECT_TRUE(report.closed);
  EXPECT_EQ(report.inconsistentEdges, 0);
  const std::vector<bender::PatchLabel> patches = bender::ReadPatchLabels(tube);
  EXPECT_EQ(patches.size(), 3u);
  if (patches.size() != 3)
  {
    return 0.0;
  }
  EXPECT_EQ(patches[0].type, bender::PatchType::Wall);
  EXPECT_EQ(patches[1].name, "inlet");
  EXPECT_EQ(patches[1].type, bender::PatchType::Inlet);
  EXPECT_EQ(patches[2].name, "outlet_1");
  EXPECT_EQ(patches[2].type, bender::PatchType::Outlet);
  return report.volume;
}

TEST(CfdVerificationTubes, AStraightTubeIsAClosedOutwardLabelledPrism)
{
  const int sides = 48;
  const double radius = 2.0, length = 30.0;
  const auto tube = bender::SweepClosedTube(bender::StraightCentreline(length, 1.0), radius, sides);
  const double section = 0.5 * sides * radius * radius * std::sin(2.0 * Pi / sides);
  EXPECT_NEAR(ClosedLabelledTubeVolume(tube), section * length, 1e-9 * section * length);
}

TEST(CfdVerificationTubes, ACurvedTubeIsATorusSection)
{
  const double radius = 2.0, bend = 10.0, angle = 300.0 * Pi / 180.0;
  const auto stations = bender::ArcCentreline(bend, angle, 0.5);
  EXPECT_NEAR(stations.back().abscissa, bend * angle, 1e-9);
  for (const bender::TubeStation& s : stations)
  {
    // On the circle of radius `bend` about (0, bend, 0), tangent to it.
    EXPECT_NEAR(std::hypot(s.centre.x, s.centre.y - bend), bend, 1e-9);
    EXPECT_NEAR(bender::Dot(s.tangent, s.centre - bender::Vec3{ 0, bend, 0 }), 0.0, 1e-9);
  }
  const auto tube = bender::SweepClosedTube(stations, radius, 64);
  // Pappus: section x centreline length, within the polygons' and chords' error.
  const double pappus = Pi * radius * radius * bend * angle;
  EXPECT_NEAR(ClosedLabelledTubeVolume(tube) / pappus, 1.0, 5e-3);
}

TEST(CfdVerificationTubes, AStraightCentrelineSpansItsEndsInEqualPieces)
{
  const auto stations = bender::StraightCentreline(-30.0, 40.0, 70);
  ASSERT_EQ(stations.size(), 71u);
  EXPECT_EQ(stations.front().centre.x, -30.0);
  EXPECT_EQ(stations.back().centre.x, 40.0);
  for (std::size_t i = 1; i < stations.size(); ++i)
  {
    EXPECT_NEAR(stations[i].centre.x - stations[i - 1].centre.x, 1.0, 1e-12);
    EXPECT_NEAR(stations[i].abscissa, stations[i].centre.x + 30.0, 1e-12);
  }
  // By length and spacing: the same stations as by ends and pieces from 0.
  const auto bySpacing = bender::StraightCentreline(24.0, 0.5);
  const auto byPieces = bender::StraightCentreline(0.0, 24.0, 48);
  ASSERT_EQ(bySpacing.size(), byPieces.size());
  for (std::size_t i = 0; i < bySpacing.size(); ++i)
  {
    EXPECT_EQ(bySpacing[i].centre.x, byPieces[i].centre.x);
  }
}

TEST(CfdVerificationTubes, AnOpenTubeIsTheClosedOnesWallWithTwoOpenEnds)
{
  const int sides = 24;
  const double radius = 3.0;
  const auto stations = bender::StraightCentreline(-30.0, 40.0, 70);
  const auto open = bender::SweepOpenTube(stations, radius, sides);
  const auto closed = bender::SweepClosedTube(stations, radius, sides);
  ASSERT_EQ(open->GetNumberOfPolys(), 2 * sides * 70);
  EXPECT_EQ(closed->GetNumberOfPolys(), open->GetNumberOfPolys() + 2 * sides);
  // No labels: no cell data and no patch table.
  EXPECT_EQ(open->GetCellData()->GetNumberOfArrays(), 0);
  EXPECT_EQ(open->GetFieldData()->GetNumberOfArrays(), 0);
  for (vtkIdType c = 0; c < open->GetNumberOfPolys(); ++c)
  {
    vtkIdType n = 0, m = 0;
    const vtkIdType *a = nullptr, *b = nullptr;
    open->GetPolys()->GetCellAtId(c, n, a);
    closed->GetPolys()->GetCellAtId(c, m, b);
    ASSERT_EQ(n, m);
    for (vtkIdType k = 0; k < n; ++k)
    {
      double p[3], q[3];
      open->GetPoint(a[k], p);
      closed->GetPoint(b[k], q);
      EXPECT_EQ(p[0], q[0]);
      EXPECT_EQ(p[1], q[1]);
      EXPECT_EQ(p[2], q[2]);
    }
  }
  const bender::MeshCheckReport report = bender::CheckMesh(open, nullptr, {});
  EXPECT_FALSE(report.closed);
  EXPECT_EQ(report.inconsistentEdges, 0);
  ASSERT_EQ(report.boundaryLoops.size(), 2u);
  EXPECT_EQ(report.boundaryLoops[0], sides);
  EXPECT_EQ(report.boundaryLoops[1], sides);
  for (vtkIdType i = 0; i < open->GetNumberOfPoints(); ++i)
  {
    double p[3];
    open->GetPoint(i, p);
    EXPECT_NEAR(std::hypot(p[1], p[2]), radius, 1e-12);
  }
  EXPECT_THROW(bender::SweepOpenTube(stations, radius, 2), bender::InputError);
  EXPECT_THROW(bender::SweepOpenTube(stations, 0.0, 24), bender::InputError);
}

TEST(CfdVerificationTubes, TheCaseTakesATubeLikeAVessel)
{
  bender::test::TemporaryFolder folder("cfd-verify-tube");
  const auto tube = bender::SweepClosedTube(bender::StraightCentreline(40.0, 1.0), 2.0, 64);
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  options.flowRate = 1e-6;
  const bender::CfdCaseResult written = bender::WriteOpenFoamCase(tube, options);
  EXPECT_EQ(written.inlet, "inlet");
  ASSERT_EQ(written.patches.size(), 3u);
  EXPECT_NEAR(written.patches[1].diameter, 4e-3, 4e-5);
}

TEST(CfdVerificationTubes, BadSweepsAndOptionsAreRefused)
{
  EXPECT_THROW(
    bender::SweepClosedTube(bender::StraightCentreline(10.0, 1.0), 0.0, 32), bender::InputError);
  EXPECT_THROW(
    bender::SweepClosedTube(bender::StraightCentreline(10.0, 1.0), 1.0, 4), bender::InputError);
  EXPECT_THROW(bender::SweepClosedTube({}, 1.0, 32), bender::InputError);
  const auto run = bendertest::RunInProcess({ "cfd-verify", "--cells-across", "2" });
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(bendertest::RunInProcess({ "cfd-verify", "--only", "bent" }).status, 2);
  // cfd-case --convergence: a refinement ratio below 1.3 is a usage error.
  EXPECT_EQ(bendertest::RunInProcess(
              { "cfd-case", "t.vtp", "-o", "c", "--convergence", "--refinement-ratio", "1.2" })
              .status,
    2);
}

} // namespace
