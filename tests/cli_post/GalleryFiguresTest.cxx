// The paper's figures (docs/gallery.md) reproduced on real meshes and measured. Each test
// applies the plans of examples/ and checks the property its figure illustrates, so that
// tearing (Fig. 8), non-rigidity inside the plateau (Fig. 9), the axis-flip jump (Fig. 10) or
// a broken vessel (Fig. 12) make the suite fail.
//
// With the environment variable BENDER_GALLERY_OUT set to a folder, every test also writes
// its meshes and a JSON file of its measured figures there; tools/make-gallery renders them.

#include "ApplyPlan.h"
#include "BenderMeshCheck.h"
#include "BenderStlExport.h"
#include "MeshIO.h"
#include "RibbonWarp.h"
#include "Screw.h"
#include "WarpPlanIO.h"
#include "WireProjection.h"
#include "vtkBenderAdaptiveSubdivisionFilter.h"
#include "vtkBenderCapFilter.h"
#include "vtkBenderWarpFilter.h"

#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkLoopSubdivisionFilter.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTriangleFilter.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
namespace fs = std::filesystem;
using bender::BlendMode;
using bender::Vec3;

const std::string External = BENDER_EXTERNAL_DATA_DIR;
const std::string TestData = BENDER_TEST_DATA_DIR;
const std::string Examples = std::string(BENDER_SOURCE_DIR) + "/examples/";

bool Have(const std::string& path)
{
  return fs::exists(path);
}

#define REQUIRE_FILE(path)                                                                         \
  if (!Have(path))                                                                                 \
  {                                                                                                \
    GTEST_FAIL() << path << " is missing: run scripts/fetch-data";                                 \
  }

// --- Output for tools/make-gallery --------------------------------------------------------

std::string GalleryOut()
{
  const char* out = std::getenv("BENDER_GALLERY_OUT");
  return out && *out ? std::string(out) : std::string();
}

void Save(vtkPolyData* mesh, const std::string& name)
{
  if (!GalleryOut().empty())
  {
    bender::WriteMesh(mesh, GalleryOut() + "/" + name);
  }
}

// The measured figures of one test: recorded as test properties and, for the gallery, as one
// flat JSON object per figure (figNN.json).
class Figures
{
public:
  explicit Figures(std::string figure)
    : Name(std::move(figure))
  {
  }
  void Add(const std::string& key, double value)
  {
    char text[64];
    std::snprintf(text, sizeof text, "%.6g", value);
    this->Values.emplace_back(key, text);
    ::testing::Test::RecordProperty(key, text);
  }
  ~Figures()
  {
    if (GalleryOut().empty())
    {
      return;
    }
    std::ofstream out(GalleryOut() + "/" + this->Name + ".json");
    out << "{\n";
    for (std::size_t i = 0; i < this->Values.size(); ++i)
    {
      out << "  \"" << this->Values[i].first << "\": " << this->Values[i].second
          << (i + 1 < this->Values.size() ? ",\n" : "\n");
    }
    out << "}\n";
  }

private:
  std::string Name;
  std::vector<std::pair<std::string, std::string>> Values;
};

// --- Mesh helpers ---------------------------------------------------------------------------

std::vector<Vec3> PointsOf(vtkPolyData* mesh)
{
  std::vector<Vec3> pts(static_cast<std::size_t>(mesh->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    pts[static_cast<std::size_t>(i)] = { p[0], p[1], p[2] };
  }
  return pts;
}

vtkSmartPointer<vtkPolyData> WithPoints(vtkPolyData* mesh, const std::vector<Vec3>& pts)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(mesh);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(pts.size()));
  for (std::size_t i = 0; i < pts.size(); ++i)
  {
    points->SetPoint(static_cast<vtkIdType>(i), pts[i].x, pts[i].y, pts[i].z);
  }
  out->SetPoints(points);
  return out;
}

// Undirected edges of the triangles.
std::vector<std::pair<std::int64_t, std::int64_t>> Edges(vtkPolyData* mesh)
{
  const std::vector<std::int64_t> tris = bender::CollectTriangles(mesh);
  std::set<std::pair<std::int64_t, std::int64_t>> edges;
  for (std::size_t t = 0; t + 2 < tris.size(); t += 3)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t a = tris[t + k], b = tris[t + (k + 1) % 3];
      edges.emplace(std::min(a, b), std::max(a, b));
    }
  }
  return { edges.begin(), edges.end() };
}

double LongestEdge(vtkPolyData* mesh)
{
  const std::vector<Vec3> pts = PointsOf(mesh);
  double longest = 0.0;
  for (const auto& e : Edges(mesh))
  {
    longest = std::max(longest, bender::Distance(pts[e.first], pts[e.second]));
  }
  return longest;
}

// The largest principal stretch over the triangles: sqrt of the largest generalised eigenvalue
// of (H^T H) x = lambda (G^T G) x, with G and H the edge matrices before and after.
double LargestTriangleStretch(vtkPolyData* before, vtkPolyData* after)
{
  const std::vector<Vec3> a = PointsOf(before), b = PointsOf(after);
  const std::vector<std::int64_t> tris = bender::CollectTriangles(before);
  double largest = 0.0;
  for (std::size_t t = 0; t + 2 < tris.size(); t += 3)
  {
    const Vec3 g1 = a[tris[t + 1]] - a[tris[t]], g2 = a[tris[t + 2]] - a[tris[t]];
    const Vec3 h1 = b[tris[t + 1]] - b[tris[t]], h2 = b[tris[t + 2]] - b[tris[t]];
    const double G11 = bender::Dot(g1, g1), G12 = bender::Dot(g1, g2), G22 = bender::Dot(g2, g2);
    const double H11 = bender::Dot(h1, h1), H12 = bender::Dot(h1, h2), H22 = bender::Dot(h2, h2);
    const double detG = G11 * G22 - G12 * G12;
    if (detG <= 0.0)
    {
      continue;
    }
    // det(H - l G) = 0: detG l^2 - (G11 H22 + G22 H11 - 2 G12 H12) l + detH = 0.
    const double detH = H11 * H22 - H12 * H12;
    const double bq = G11 * H22 + G22 * H11 - 2.0 * G12 * H12;
    const double disc = std::max(0.0, bq * bq - 4.0 * detG * detH);
    const double l = (bq + std::sqrt(disc)) / (2.0 * detG);
    largest = std::max(largest, std::sqrt(std::max(0.0, l)));
  }
  return largest;
}

double MaxDisplacement(vtkPolyData* before, vtkPolyData* after)
{
  const std::vector<Vec3> a = PointsOf(before), b = PointsOf(after);
  double largest = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
  {
    largest = std::max(largest, bender::Distance(a[i], b[i]));
  }
  return largest;
}

bool AllFinite(vtkPolyData* mesh)
{
  for (const Vec3& p : PointsOf(mesh))
  {
    if (!bender::IsFinite(p))
    {
      return false;
    }
  }
  return true;
}

// One warp through the production workflow (bender::ApplyWarp: the warp filter, or the
// subdivision filter alone when the warp carries a subdivision object).
vtkSmartPointer<vtkPolyData> WarpOnce(vtkPolyData* mesh,
  const bender::WarpSpec& spec,
  BlendMode blend = BlendMode::TwoProjections)
{
  bender::ApplyPlanOptions options;
  options.blend = blend;
  try
  {
    return bender::ApplyWarp(mesh, spec, options);
  }
  catch (const bender::Error& e)
  {
    ADD_FAILURE() << e.what();
    return vtkSmartPointer<vtkPolyData>::New();
  }
}

// A whole plan through bender::ApplyPlan, the rule bender-cli and the GUI use.
vtkSmartPointer<vtkPolyData> WarpByPlan(vtkPolyData* mesh, const bender::WarpPlan& plan)
{
  try
  {
    return bender::ApplyPlan(mesh, plan).output;
  }
  catch (const bender::Error& e)
  {
    ADD_FAILURE() << e.what();
    return vtkSmartPointer<vtkPolyData>::New();
  }
}

bender::WarpPlan Plan(const std::string& name)
{
  return bender::ReadWarpPlan(Examples + name);
}

// The warp of spec 6 evaluated point by point with the motion at s given by `motion` (so that
// the test can swap the continuity lift for the minimal screws).
template<typename MotionFn>
Vec3 WarpPoint(const bender::RibbonWarp& warp, const Vec3& p, MotionFn motion)
{
  const bender::WireProjections pr =
    bender::ProjectOntoWire(warp.Initial().Wire(), p, warp.Spec().radius);
  if (pr.count == 0)
  {
    return p;
  }
  const double f0 = warp.Weight(pr.items[0].distance);
  if (pr.count == 1)
  {
    return bender::ApplyScrewFraction(motion(pr.items[0].s), p, f0);
  }
  const double f1 = warp.Weight(pr.items[1].distance);
  if (f0 + f1 <= 0.0)
  {
    return p;
  }
  const double f = 1.0 - (1.0 - f0) * (1.0 - f1);
  const Vec3 p0 = bender::ApplyScrewFraction(motion(pr.items[0].s), p, f);
  const Vec3 p1 = bender::ApplyScrewFraction(motion(pr.items[1].s), p, f);
  return (p0 * f0 + p1 * f1) * (1.0 / (f0 + f1));
}

// The minimal screw at s (rotation angle <= pi, no sign continuity): the warp without the lift.
bender::DualQuaternion MinimalMotion(const bender::RibbonWarp& warp, double s)
{
  const bender::Frame c = warp.Initial().FrameAt(s), cp = warp.Final().FrameAt(s);
  bender::Quaternion q =
    bender::QuaternionOfFrame(cp) * bender::Conjugate(bender::QuaternionOfFrame(c));
  if (q.w < 0.0)
  {
    q = -q;
  }
  return bender::MotionBetween(c, cp, q);
}

// Largest difference of displacement between the two ends of an edge.
double LargestNeighbourJump(vtkPolyData* before, const std::vector<Vec3>& after)
{
  const std::vector<Vec3> a = PointsOf(before);
  double largest = 0.0;
  for (const auto& e : Edges(before))
  {
    const Vec3 da = after[e.first] - a[e.first], db = after[e.second] - a[e.second];
    largest = std::max(largest, bender::Distance(da, db));
  }
  return largest;
}

vtkSmartPointer<vtkPolyData> Read(const std::string& path)
{
  return bender::ReadMesh(path);
}

// sphere.off (162 points) refined twice by Loop subdivision and put back on its sphere of
// radius 0.5: a smooth sphere of 5120 triangles.
vtkSmartPointer<vtkPolyData> FineSphere()
{
  vtkNew<vtkLoopSubdivisionFilter> loop;
  loop->SetInputData(Read(External + "/sphere.off"));
  loop->SetNumberOfSubdivisions(2);
  loop->Update();
  std::vector<Vec3> pts = PointsOf(loop->GetOutput());
  for (Vec3& p : pts)
  {
    p = p * (0.5 / bender::Norm(p));
  }
  return WithPoints(loop->GetOutput(), pts);
}

bender::MeshCheckReport Check(vtkPolyData* mesh, vtkPolyData* before = nullptr)
{
  return bender::CheckMesh(mesh, before);
}

std::string Problems(const bender::MeshCheckReport& report)
{
  std::string all;
  for (const std::string& p : report.problems)
  {
    all += p + "; ";
  }
  return all;
}
} // namespace

// --- Fig. 1: the cow in 6 warps -------------------------------------------------------------

TEST(GalleryFigures, Fig01CowInSixWarps)
{
  REQUIRE_FILE(External + "/cow.off");
  const auto cow = Read(External + "/cow.off");
  const bender::WarpPlan plan = Plan("fig01-cow.bender.json");
  ASSERT_EQ(plan.warps.size(), 6u);
  const auto warped = WarpByPlan(cow, plan);
  ASSERT_EQ(warped->GetNumberOfPoints(), cow->GetNumberOfPoints());
  ASSERT_TRUE(AllFinite(warped));
  const auto report = Check(warped, cow);
  Figures fig("fig01");
  fig.Add("points", static_cast<double>(cow->GetNumberOfPoints()));
  fig.Add("max_displacement", MaxDisplacement(cow, warped));
  fig.Add("flipped_triangles", static_cast<double>(report.flippedTriangles));
  fig.Add("self_intersections", static_cast<double>(report.selfIntersections));
  // The legs and the neck move by a good fraction of the cow's length (1.0). cow.off itself has
  // 83 intersecting triangle pairs (hooves and horns); the counts are recorded, not asserted.
  // Flipped triangles (n_before . n_after < 0) are recorded only: a leg bent by 75 degrees
  // turns some of its triangles by more than 90 degrees.
  EXPECT_GT(MaxDisplacement(cow, warped), 0.1);
  fig.Add("self_intersections_before", static_cast<double>(Check(cow).selfIntersections));
  Save(warped, "fig01-cow.vtp");
}

// --- Fig. 2: the bunny's ear bent, then twisted ----------------------------------------------

TEST(GalleryFigures, Fig02BunnyEarBentThenTwisted)
{
  REQUIRE_FILE(External + "/bunny00.off");
  const auto bunny = Read(External + "/bunny00.off");
  const auto bent = WarpByPlan(bunny, Plan("fig02-bunny-ear-bend.bender.json"));
  const auto twisted = WarpByPlan(bunny, Plan("fig02-bunny-ear-bend-twist.bender.json"));
  ASSERT_TRUE(AllFinite(bent));
  ASSERT_TRUE(AllFinite(twisted));
  Figures fig("fig02");
  fig.Add("bend_max_displacement", MaxDisplacement(bunny, bent));
  fig.Add("twist_max_displacement", MaxDisplacement(bent, twisted));
  const auto bentCheck = Check(bent, bunny);
  const auto twistCheck = Check(twisted, bent);
  fig.Add("bend_flipped_triangles", static_cast<double>(bentCheck.flippedTriangles));
  fig.Add("twist_flipped_triangles", static_cast<double>(twistCheck.flippedTriangles));
  EXPECT_GT(MaxDisplacement(bunny, bent), 0.05);
  EXPECT_GT(MaxDisplacement(bent, twisted), 0.02);
  EXPECT_EQ(bentCheck.selfIntersections, 0);
  EXPECT_EQ(twistCheck.selfIntersections, 0);
  // Only the ear moves: the bottom half of the bunny stays where it was.
  const std::vector<Vec3> a = PointsOf(bunny), b = PointsOf(twisted);
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    if (a[i].y < 0.0)
    {
      ASSERT_EQ(bender::Distance(a[i], b[i]), 0.0) << "point " << i;
    }
  }
  Save(bent, "fig02-bunny-bent.vtp");
  Save(twisted, "fig02-bunny-twisted.vtp");
}

// --- Fig. 8: tearing with a single projection -----------------------------------------------

TEST(GalleryFigures, Fig08TwoProjectionsDoNotTear)
{
  REQUIRE_FILE(External + "/sphere.off");
  const auto sphere = FineSphere();
  const bender::WarpPlan plan = Plan("fig08-sphere-circle.bender.json");
  ASSERT_EQ(plan.warps.size(), 1u);
  const auto two = WarpOnce(sphere, plan.warps[0], BlendMode::TwoProjections);
  const auto single = WarpOnce(sphere, plan.warps[0], BlendMode::SingleProjection);
  ASSERT_TRUE(AllFinite(two));
  ASSERT_TRUE(AllFinite(single));
  const double before = LongestEdge(sphere);
  const double edgeTwo = LongestEdge(two), edgeSingle = LongestEdge(single);
  const double stretchTwo = LargestTriangleStretch(sphere, two);
  const double stretchSingle = LargestTriangleStretch(sphere, single);
  Figures fig("fig08");
  fig.Add("triangles", static_cast<double>(sphere->GetNumberOfPolys()));
  fig.Add("longest_edge_before", before);
  fig.Add("longest_edge_single", edgeSingle);
  fig.Add("longest_edge_two", edgeTwo);
  fig.Add("stretch_single", stretchSingle);
  fig.Add("stretch_two", stretchTwo);
  // Single projection tears: edges across the gap of the circle are pulled apart.
  EXPECT_GT(edgeSingle, 5.0 * before);
  EXPECT_LT(edgeTwo, 0.25 * edgeSingle);
  EXPECT_LT(stretchTwo, 0.25 * stretchSingle);
  Save(sphere, "fig08-sphere.vtp");
  Save(two, "fig08-two.vtp");
  Save(single, "fig08-single.vtp");
}

// --- Fig. 9: bell vs plateau on the same ribbons ----------------------------------------------

TEST(GalleryFigures, Fig09PlateauKeepsATubeRigid)
{
  const auto tube = Read(TestData + "/conformance/tube.off");
  const bender::WarpPlan bell = Plan("fig09-tube-bell.bender.json");
  const bender::WarpPlan plateau = Plan("fig09-tube-plateau.bender.json");
  ASSERT_EQ(bell.warps.size(), 1u);
  ASSERT_EQ(plateau.warps.size(), 1u);
  const bender::WarpSpec& spec = plateau.warps[0];
  ASSERT_EQ(spec.decay.shape, bender::DecayShape::Plateau);
  const bender::RibbonWarp warp(spec);
  // The final ribbon is a rigid motion G of the initial one: every screw is G.
  const bender::DualQuaternion g = warp.MotionAt(0.0);
  for (double s : { 0.25, 0.5, 1.0 })
  {
    const Vec3 probe{ 30, 3, -2 };
    ASSERT_LT(
      bender::Distance(bender::ApplyMotion(warp.MotionAt(s), probe), bender::ApplyMotion(g, probe)),
      1e-9 * 50);
  }
  const auto withPlateau = WarpByPlan(tube, plateau);
  const auto withBell = WarpByPlan(tube, bell);
  const std::vector<Vec3> p0 = PointsOf(tube), pp = PointsOf(withPlateau), pb = PointsOf(withBell);
  const double inner = spec.decay.plateau * spec.radius;
  double sumPlateau = 0.0, sumBell = 0.0;
  std::size_t inside = 0;
  for (std::size_t i = 0; i < p0.size(); ++i)
  {
    const auto pr = bender::ProjectOntoWire(warp.Initial().Wire(), p0[i], spec.radius);
    // Inside the plateau of every projection the point has.
    bool all = pr.count > 0;
    for (int k = 0; k < pr.count; ++k)
    {
      all = all && pr.items[k].distance < inner;
    }
    if (!all)
    {
      continue;
    }
    const Vec3 rigid = bender::ApplyMotion(g, p0[i]);
    sumPlateau += std::pow(bender::Distance(pp[i], rigid), 2);
    sumBell += std::pow(bender::Distance(pb[i], rigid), 2);
    ++inside;
  }
  ASSERT_GT(inside, 100u);
  const double size = tube->GetLength();
  const double rmsPlateau = std::sqrt(sumPlateau / static_cast<double>(inside));
  const double rmsBell = std::sqrt(sumBell / static_cast<double>(inside));
  Figures fig("fig09");
  fig.Add("points_inside_plateau", static_cast<double>(inside));
  fig.Add("size", size);
  fig.Add("rms_from_rigid_plateau", rmsPlateau);
  fig.Add("rms_from_rigid_bell", rmsBell);
  fig.Add("rms_from_rigid_plateau_relative", rmsPlateau / size);
  EXPECT_LT(rmsPlateau, 1e-9 * size);
  EXPECT_GT(rmsBell, 1e-2 * size);
  Save(withBell, "fig09-bell.vtp");
  Save(withPlateau, "fig09-plateau.vtp");
}

// --- Fig. 10: the screw axis flips along the wire --------------------------------------------

TEST(GalleryFigures, Fig10ContinuityLiftRemovesTheJump)
{
  const auto tube = Read(TestData + "/conformance/tube.off");
  const bender::WarpPlan plan = Plan("fig10-tube-flip.bender.json");
  ASSERT_EQ(plan.warps.size(), 1u);
  const bender::RibbonWarp warp(plan.warps[0]);
  ASSERT_TRUE(warp.FlipOccurred()) << "the plan must make the minimal screw flip";
  const std::vector<Vec3> p0 = PointsOf(tube);
  std::vector<Vec3> lifted(p0.size()), minimal(p0.size());
  const auto liftedMotion = [&](double s) { return warp.MotionAt(s); };
  const auto minimalMotion = [&](double s) { return MinimalMotion(warp, s); };
  for (std::size_t i = 0; i < p0.size(); ++i)
  {
    lifted[i] = WarpPoint(warp, p0[i], liftedMotion);
    minimal[i] = WarpPoint(warp, p0[i], minimalMotion);
  }
  // The point-by-point warp with the lift is the production warp.
  const auto production = WarpByPlan(tube, plan);
  const std::vector<Vec3> pp = PointsOf(production);
  for (std::size_t i = 0; i < p0.size(); ++i)
  {
    ASSERT_LT(bender::Distance(lifted[i], pp[i]), 1e-9 * tube->GetLength()) << "point " << i;
  }
  // The paper's figure: the surface swept by the helix trajectories H(s, f) = SCREW_F(P_s; f),
  // f in [0, 1], of the initial wire's points, on a grid of ns x nf samples.
  const int ns = 400, nf = 21;
  const auto helix = [&](auto motion)
  {
    std::vector<Vec3> grid;
    for (int i = 0; i < ns; ++i)
    {
      const double s = i / (ns - 1.0);
      const Vec3 p = warp.Initial().FrameAt(s).origin;
      for (int j = 0; j < nf; ++j)
      {
        grid.push_back(bender::ApplyScrewFraction(motion(s), p, j / (nf - 1.0)));
      }
    }
    return grid;
  };
  const std::vector<Vec3> sweptLift = helix(liftedMotion), sweptMinimal = helix(minimalMotion);
  // Largest distance between trajectories of neighbouring wire points (same f).
  const auto jump = [&](const std::vector<Vec3>& grid)
  {
    double largest = 0.0;
    for (int i = 0; i + 1 < ns; ++i)
    {
      for (int j = 0; j < nf; ++j)
      {
        largest = std::max(largest, bender::Distance(grid[i * nf + j], grid[(i + 1) * nf + j]));
      }
    }
    return largest;
  };
  const double jumpLift = jump(sweptLift), jumpMinimal = jump(sweptMinimal);
  Figures fig("fig10");
  fig.Add("wire_samples", ns);
  fig.Add("wire_sample_spacing", warp.Initial().Wire().Length() / (ns - 1));
  fig.Add("largest_jump_with_lift", jumpLift);
  fig.Add("largest_jump_without_lift", jumpMinimal);
  fig.Add("mesh_largest_neighbour_jump_with_lift", LargestNeighbourJump(tube, lifted));
  fig.Add("mesh_largest_neighbour_jump_without_lift", LargestNeighbourJump(tube, minimal));
  EXPECT_LT(jumpLift, 0.1 * jumpMinimal);
  EXPECT_GT(jumpMinimal, 0.1 * warp.Initial().Wire().Length());
  if (!GalleryOut().empty())
  {
    const auto surface = [&](const std::vector<Vec3>& grid)
    {
      auto mesh = vtkSmartPointer<vtkPolyData>::New();
      vtkNew<vtkPoints> points;
      for (const Vec3& p : grid)
      {
        points->InsertNextPoint(p.x, p.y, p.z);
      }
      vtkNew<vtkCellArray> cells;
      for (int i = 0; i + 1 < ns; ++i)
      {
        for (int j = 0; j + 1 < nf; ++j)
        {
          const vtkIdType a = i * nf + j, b = (i + 1) * nf + j;
          const vtkIdType t0[3] = { a, b, b + 1 }, t1[3] = { a, b + 1, a + 1 };
          cells->InsertNextCell(3, t0);
          cells->InsertNextCell(3, t1);
        }
      }
      mesh->SetPoints(points);
      mesh->SetPolys(cells);
      return mesh;
    };
    Save(surface(sweptLift), "fig10-helix-lift.vtp");
    Save(surface(sweptMinimal), "fig10-helix-nolift.vtp");
  }
  Save(production, "fig10-lift.vtp");
  Save(WithPoints(tube, minimal), "fig10-nolift.vtp");
}

// --- Fig. 11: adaptive subdivision ------------------------------------------------------------

TEST(GalleryFigures, Fig11SubdivisionRefinesWhereTheWarpBends)
{
  REQUIRE_FILE(External + "/plane.off");
  const auto plane = Read(External + "/plane.off");
  const auto coarse = WarpByPlan(plane, Plan("fig11-plane-horn-coarse.bender.json"));
  const bender::WarpPlan refinedPlan = Plan("fig13-plane-horn.bender.json");
  ASSERT_TRUE(refinedPlan.warps[0].subdivision);
  vtkNew<vtkBenderAdaptiveSubdivisionFilter> subdivide;
  subdivide->SetInputData(plane);
  subdivide->SetWarp(refinedPlan.warps[0]);
  subdivide->Update();
  ASSERT_EQ(subdivide->GetLastError(), "");
  vtkPolyData* refined = subdivide->GetOutput();
  // The same warp: old vertices land where the coarse warp puts them.
  const std::vector<Vec3> a = PointsOf(coarse), b = PointsOf(refined);
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    ASSERT_LT(bender::Distance(a[i], b[i]), 1e-12 * 10) << "point " << i;
  }
  Figures fig("fig11");
  fig.Add("triangles_before", static_cast<double>(coarse->GetNumberOfPolys()));
  fig.Add("triangles_after", static_cast<double>(refined->GetNumberOfPolys()));
  fig.Add("passes", subdivide->GetNumberOfPassesRun());
  fig.Add("tolerance", subdivide->GetTolerance());
  fig.Add("max_deviation_last_pass", subdivide->GetLastMaximumDeviation());
  fig.Add("longest_edge_before", LongestEdge(coarse));
  fig.Add("longest_edge_after", LongestEdge(refined));
  EXPECT_GT(refined->GetNumberOfPolys(), 2 * coarse->GetNumberOfPolys());
  EXPECT_LT(LongestEdge(refined), 0.5 * LongestEdge(coarse));
  const auto report = Check(refined);
  EXPECT_EQ(report.nonManifoldEdges, 0);
  EXPECT_EQ(report.boundaryLoops.size(), 1u);
  Save(coarse, "fig11-coarse.vtp");
  Save(refined, "fig11-subdivided.vtp");
}

// --- Fig. 12: the aneurysm junction, one vessel bent, checked and exported --------------------

TEST(GalleryFigures, Fig12AneurysmVesselBentStaysClean)
{
  REQUIRE_FILE(External + "/aneurysm_data.stl");
  const auto vessel = Read(External + "/aneurysm_data.stl");
  const auto bent = WarpByPlan(vessel, Plan("fig12-aneurysm-bend.bender.json"));
  const auto before = Check(vessel);
  const auto after = Check(bent, vessel);
  EXPECT_TRUE(before.Clean()) << Problems(before);
  EXPECT_TRUE(after.Clean()) << Problems(after);
  EXPECT_TRUE(after.flipsChecked);
  EXPECT_EQ(after.flippedTriangles, 0);
  EXPECT_EQ(after.selfIntersections, 0);
  EXPECT_EQ(after.boundaryLoops, before.boundaryLoops) << "no new boundary";
  EXPECT_EQ(after.components, before.components);
  // Capped for CFD: closed, consistently oriented, three caps.
  vtkNew<vtkBenderCapFilter> cap;
  cap->SetInputData(bent);
  cap->Update();
  ASSERT_EQ(cap->GetLastError(), "");
  const auto capped = Check(cap->GetOutput());
  bender::MeshCheckOptions closed;
  closed.requireClosed = true;
  const auto cappedClosed = bender::CheckMesh(cap->GetOutput(), nullptr, closed);
  EXPECT_TRUE(cappedClosed.Clean()) << Problems(cappedClosed);
  EXPECT_EQ(cap->GetNumberOfCaps(), static_cast<int>(before.boundaryLoops.size()));
  EXPECT_GT(capped.volume, 0.0);
  Figures fig("fig12");
  fig.Add("triangles", static_cast<double>(after.triangles));
  fig.Add("boundary_loops_before", static_cast<double>(before.boundaryLoops.size()));
  fig.Add("boundary_loops_after", static_cast<double>(after.boundaryLoops.size()));
  fig.Add("flipped_triangles", static_cast<double>(after.flippedTriangles));
  fig.Add("self_intersections_before", static_cast<double>(before.selfIntersections));
  fig.Add("self_intersections_after", static_cast<double>(after.selfIntersections));
  fig.Add("max_displacement_mm", MaxDisplacement(vessel, bent));
  fig.Add("caps", cap->GetNumberOfCaps());
  fig.Add("capped_volume_mm3", capped.volume);
  fig.Add("min_angle_before_deg", before.minimumAngle.min);
  fig.Add("min_angle_after_deg", after.minimumAngle.min);
  Save(bent, "fig12-aneurysm-bent.vtp");
}

// --- Fig. 13 and 14: single warps on a plane and on a tube ------------------------------------

namespace
{
struct Shape
{
  const char* figure;
  const char* plan;
  const char* mesh;
  const char* out;
};

void CheckShape(const Shape& shape, Figures& fig, const std::string& key)
{
  const auto mesh = Read(shape.mesh);
  const bender::WarpPlan plan = Plan(shape.plan);
  ASSERT_EQ(plan.warps.size(), 1u) << shape.plan;
  const auto warped = WarpByPlan(mesh, plan);
  ASSERT_TRUE(AllFinite(warped)) << shape.plan;
  const bool same = warped->GetNumberOfPoints() == mesh->GetNumberOfPoints();
  const auto report = Check(warped, same && !plan.warps[0].subdivision ? mesh.Get() : nullptr);
  EXPECT_EQ(report.nonManifoldEdges, 0) << shape.plan;
  // Bends and twists turn triangles by more than 90 degrees: flips are recorded, not asserted.
  EXPECT_EQ(report.selfIntersections, 0) << shape.plan;
  fig.Add(key + "_triangles", static_cast<double>(report.triangles));
  fig.Add(key + "_flipped_triangles", static_cast<double>(report.flippedTriangles));
  fig.Add(key + "_self_intersections", static_cast<double>(report.selfIntersections));
  fig.Add(key + "_min_angle_deg", report.minimumAngle.min);
  Save(warped, shape.out);
}
} // namespace

TEST(GalleryFigures, Fig13FeaturesOnAPlane)
{
  REQUIRE_FILE(External + "/plane.off");
  const std::string plane = External + "/plane.off";
  Figures fig("fig13");
  for (const char* name : { "bowl", "wave", "fin", "emboss-s", "horn" })
  {
    const std::string plan = std::string("fig13-plane-") + name + ".bender.json";
    const std::string out = std::string("fig13-") + name + ".vtp";
    CheckShape({ "fig13", plan.c_str(), plane.c_str(), out.c_str() }, fig, name);
  }
}

TEST(GalleryFigures, Fig14FeaturesOfATube)
{
  const std::string tube = TestData + "/conformance/tube.off";
  Figures fig("fig14");
  for (const char* name : { "bend", "twist", "stretch", "curl", "hook" })
  {
    const std::string plan = std::string("fig14-tube-") + name + ".bender.json";
    const std::string out = std::string("fig14-") + name + ".vtp";
    CheckShape({ "fig14", plan.c_str(), tube.c_str(), out.c_str() }, fig, name);
  }
}
