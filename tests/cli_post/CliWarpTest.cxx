// bender-cli warp end to end: the real executable on real files.

#include "MeshIO.h"
#include "RibbonWarp.h"
#include "WarpPlanIO.h"

#include "CliPostTestUtilities.h"

#include <vtkPolyData.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace
{
using clitest::Cli;
using clitest::Data;
using clitest::External;
using clitest::Result;

class CliWarp : public clitest::ScratchTest
{
protected:
  // stdout and stderr together: the messages are checked wherever they go.
  Result RunCli(const std::string& args) const
  {
    Result r = this->Run(args);
    r.output += r.errors;
    return r;
  }
  // Files left in the scratch folder (a failed command must leave none).
  int FileCount() const { return static_cast<int>(this->Files().size()); }
};

TEST_F(CliWarp, HelpAndUsage)
{
  Result r = RunCli("--help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("warp"), std::string::npos);
  r = RunCli("warp --help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("IN_MESH PLAN OUT_MESH"), std::string::npos);
  r = RunCli("warp only-one-argument");
  EXPECT_EQ(r.status, 2);
  r = RunCli("no-such-command");
  EXPECT_EQ(r.status, 2);
}

TEST_F(CliWarp, ReproducesTheConformanceResultsExactly)
{
  for (const std::string name : { "bend90", "twist150", "semicircle_chain" })
  {
    const std::string out = this->Tmp(name + ".vtp");
    const Result r = RunCli("warp " + Data + "/conformance/tube.off " + Data + "/conformance/" +
      name + ".bender.json " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    auto result = bender::ReadMesh(out);
    auto expected = bender::ReadMesh(Data + "/conformance/" + name + ".expected.off");
    ASSERT_EQ(result->GetNumberOfPoints(), expected->GetNumberOfPoints());
    ASSERT_EQ(result->GetNumberOfPolys(), expected->GetNumberOfPolys());
    double worst = 0.0;
    for (vtkIdType i = 0; i < result->GetNumberOfPoints(); ++i)
    {
      double a[3], b[3];
      result->GetPoint(i, a);
      expected->GetPoint(i, b);
      worst = std::max(worst, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
    }
    EXPECT_LT(worst, 50.0 * 1e-9) << name;
  }
}

TEST_F(CliWarp, WarpsTheCowLocallyWithoutNaN)
{
  const std::string cow = External + "/cow.off";
  ASSERT_TRUE(fs::exists(cow)) << cow << " missing: run scripts/fetch-data";
  const std::string plan = Data + "/cli_warp/cow_bend.bender.json";
  // PLY keeps the vertex order (STL would weld the cow's duplicate vertex).
  const std::string out = this->Tmp("cow_warped.ply");
  const Result ok = RunCli("warp " + cow + " " + plan + " " + out);
  ASSERT_EQ(ok.status, 0) << ok.output;
  auto before = bender::ReadMesh(cow);
  auto after = bender::ReadMesh(out);
  ASSERT_EQ(after->GetNumberOfPolys(), before->GetNumberOfPolys());
  ASSERT_EQ(after->GetNumberOfPoints(), before->GetNumberOfPoints());
  const bender::WarpPlan p = bender::ReadWarpPlan(plan);
  const bender::RibbonWarp warp(p.warps[0]);
  int moved = 0;
  for (vtkIdType i = 0; i < before->GetNumberOfPoints(); ++i)
  {
    double a[3], b[3];
    before->GetPoint(i, a);
    after->GetPoint(i, b);
    ASSERT_TRUE(std::isfinite(b[0]) && std::isfinite(b[1]) && std::isfinite(b[2]));
    const double shift = std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
    const auto pr =
      bender::ProjectOntoWire(warp.Initial().Wire(), { a[0], a[1], a[2] }, p.warps[0].radius);
    if (pr.count == 0)
    {
      // PLY stores float: an untouched point round-trips within float precision.
      EXPECT_LT(shift, 1e-6) << "point " << i << " outside R moved";
    }
    else if (shift > 1e-3)
    {
      ++moved;
    }
  }
  EXPECT_GT(moved, 100);
}

TEST_F(CliWarp, BadInputsGiveOneLineAndNoOutput)
{
  const std::string tube = Data + "/conformance/tube.off";
  const std::string plan = Data + "/conformance/bend90.bender.json";
  struct Case
  {
    std::string args;
    std::string expect;
  };
  const std::string out = this->Tmp("out.stl");
  const Case cases[] = {
    { "warp " + this->Tmp("missing.off") + " " + plan + " " + out, "missing.off" },
    { "warp " + Data + "/cli_warp/truncated.stl " + plan + " " + out, "truncated.stl" },
    { "warp " + tube + " " + this->Tmp("missing.bender.json") + " " + out, "missing.bender.json" },
    { "warp " + tube + " " + Data + "/cli_warp/coincident.bender.json " + out, "warps[0].final" },
    { "warp " + tube + " " + plan + " " + this->Tmp("out.xyz"), "out.xyz" },
  };
  for (const Case& c : cases)
  {
    const Result r = RunCli(c.args);
    EXPECT_EQ(r.status, 1) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("Segmentation fault"), std::string::npos);
    EXPECT_EQ(this->FileCount(), 0) << "a failed warp left a file behind: " << c.args;
  }
}

TEST_F(CliWarp, MixedPolygonsAreWarpedAndAPointCloudIsRefused)
{
  // Triangles and a quad: polygons pass through unchanged, points are warped.
  const std::string mixed = this->Tmp("mixed.off");
  {
    std::ofstream o(mixed);
    o << "OFF\n6 3 0\n0 0 0\n20 -3 0\n20 3 0\n30 -3 1\n30 3 1\n100 0 0\n"
         "3 0 1 2\n4 1 3 4 2\n3 3 5 4\n";
  }
  const std::string out = this->Tmp("mixed_out.vtp");
  const Result ok = RunCli("warp " + mixed + " " + Data + "/conformance/bend90.bender.json " + out);
  ASSERT_EQ(ok.status, 0) << ok.output;
  auto result = bender::ReadMesh(out);
  ASSERT_EQ(result->GetNumberOfPolys(), 3);
  ASSERT_EQ(result->GetNumberOfPoints(), 6);
  double p[3];
  result->GetPoint(3, p);
  EXPECT_GT(std::hypot(p[0] - 30.0, p[1] + 3.0, p[2] - 1.0), 1.0) << "inside R, must move";
  result->GetPoint(5, p);
  EXPECT_EQ(p[0], 100.0);

  const std::string cloud = this->Tmp("cloud.off");
  {
    std::ofstream o(cloud);
    o << "OFF\n2 0 0\n0 0 0\n1 0 0\n";
  }
  const Result refused =
    RunCli("warp " + cloud + " " + Data + "/conformance/bend90.bender.json " + this->Tmp("c.vtp"));
  EXPECT_EQ(refused.status, 1);
  EXPECT_NE(refused.output.find("cloud.off"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(this->Tmp("c.vtp")));
}

TEST_F(CliWarp, NeverOverwritesItsInput)
{
  const std::string copy = this->Tmp("tube.off");
  fs::copy_file(Data + "/conformance/tube.off", copy);
  const auto sizeBefore = fs::file_size(copy);
  const Result r = RunCli("warp " + copy + " " + Data + "/conformance/bend90.bender.json " + copy);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("overwrite"), std::string::npos) << r.output;
  EXPECT_EQ(fs::file_size(copy), sizeBefore);
  // The same file through another spelling of its path.
  const Result r2 = RunCli("warp " + copy + " " + Data + "/conformance/bend90.bender.json " +
    (this->Dir / "." / "tube.off").string());
  EXPECT_EQ(r2.status, 1);
  EXPECT_EQ(fs::file_size(copy), sizeBefore);
}

} // namespace
