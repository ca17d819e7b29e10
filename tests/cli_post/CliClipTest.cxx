// bender-cli clip (in-process): the gmsh aneurysm clipped, extended, capped and labelled into
// a VTP; user names and clip distances; one-line errors with a non-zero exit and no output for
// bad input (an end no centerline reaches, a --end off its vessel: nothing written); the input
// is never overwritten.

#include "InProcessCli.h"

#include "BenderMeshCheck.h"
#include "MeshIO.h"
#include "PatchLabels.h"
#include "VesselCenterlines.h"
#include "VesselTestUtilities.h"

#include <gtest/gtest.h>

#include <vtkPolyData.h>

#include <filesystem>
#include <string>

namespace
{
const std::string Aneurysm = std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl";

std::string Temp(const std::string& name)
{
  return (std::filesystem::temp_directory_path() / ("bender_cli_clip_" + name)).string();
}

int Lines(const std::string& text)
{
  int n = 0;
  for (char c : text)
  {
    n += c == '\n' ? 1 : 0;
  }
  return n;
}
} // namespace

TEST(CliClip, AneurysmIsClippedCappedAndLabelled)
{
  const std::string out = Temp("aneurysm.vtp");
  std::filesystem::remove(out);
  const bendertest::CliRun run = bendertest::RunInProcess({ "clip", Aneurysm, "-o", out });
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("3 ends"), std::string::npos) << run.out;
  auto mesh = bender::ReadMesh(out);
  bender::MeshCheckOptions check;
  check.requireClosed = true;
  check.selfIntersections = false;
  const auto report = bender::CheckMesh(mesh, nullptr, check);
  EXPECT_TRUE(report.Clean()) << bender::FormatReportText(report, out);
  const auto labels = bender::ReadPatchLabels(mesh);
  ASSERT_EQ(labels.size(), 4u);
  EXPECT_EQ(labels[1].name, "inlet");
  EXPECT_EQ(labels[1].type, bender::PatchType::Inlet);
  EXPECT_EQ(labels[2].name, "outlet_1");
  EXPECT_EQ(labels[3].name, "outlet_2");
  std::filesystem::remove(out);
}

TEST(CliClip, NamesDistancesAndNoExtension)
{
  // First the plain clip, to learn where the ends are.
  const std::string first = Temp("plain.vtp");
  bendertest::CliRun run = bendertest::RunInProcess(
    { "clip", Aneurysm, "-o", first, "--extend-inlet", "0", "--extend-outlet", "0" });
  ASSERT_EQ(run.status, 0) << run.err;
  auto mesh = bender::ReadMesh(first);
  // The centre of the cap of outlet_2 (id 4): mean of its points.
  const std::vector<int> ids = bender::CellPatchIds(mesh);
  double c[3] = { 0, 0, 0 };
  int count = 0;
  for (vtkIdType t = 0; t < mesh->GetNumberOfCells(); ++t)
  {
    if (ids[static_cast<std::size_t>(t)] != 4)
    {
      continue;
    }
    double p[3];
    mesh->GetPoint(mesh->GetCell(t)->GetPointId(0), p);
    for (int a = 0; a < 3; ++a)
    {
      c[a] += p[a];
    }
    ++count;
  }
  ASSERT_GT(count, 0);
  const std::string at = std::to_string(c[0] / count) + "," + std::to_string(c[1] / count) + "," +
    std::to_string(c[2] / count);
  const std::string out = Temp("named.vtp");
  run = bendertest::RunInProcess(
    { "clip", Aneurysm, "-o", out, "--name", at + "=basilar", "--end", at + ":12", "--no-cap" });
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("basilar"), std::string::npos) << run.out;
  auto open = bender::ReadMesh(out);
  EXPECT_EQ(bender::CheckMesh(open).boundaryLoops.size(), 3u); // --no-cap
  std::filesystem::remove(first);
  std::filesystem::remove(out);
}

TEST(CliClip, BadInputIsOneLineAndNonZero)
{
  const std::string out = Temp("bad.vtp");
  std::filesystem::remove(out);
  // A clip position on no vessel.
  bendertest::CliRun run =
    bendertest::RunInProcess({ "clip", Aneurysm, "-o", out, "--end", "900,900,900" });
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(Lines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find("is not on a vessel"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  // Malformed arguments: usage errors.
  run = bendertest::RunInProcess({ "clip", Aneurysm, "-o", out, "--end", "1,2" });
  EXPECT_NE(run.status, 0);
  run = bendertest::RunInProcess({ "clip", Aneurysm, "-o", out, "--end", "1,2,3:-4" });
  EXPECT_EQ(run.status, 2);
  run = bendertest::RunInProcess({ "clip", Aneurysm, "-o", out, "--name", "1,2,3" });
  EXPECT_EQ(run.status, 2);
  // One value per flag (repeat the flag per end): a second value after one flag is not taken.
  run = bendertest::RunInProcess(
    { "clip", Aneurysm, "-o", out, "--end", "900,900,900", "901,900,900" });
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(run.err.find("901,900,900"), std::string::npos) << run.err;
  run = bendertest::RunInProcess(
    { "clip", Aneurysm, "-o", out, "--name", "1,2,3=a", "4,5,6=b", "--no-clip" });
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(run.err.find("4,5,6=b"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  run = bendertest::RunInProcess({ "clip", Aneurysm, "-o", out, "--extend-inlet", "-1" });
  EXPECT_EQ(run.status, 2);
  run = bendertest::RunInProcess({ "clip", Aneurysm });
  EXPECT_EQ(run.status, 2);
  // Never the input.
  run = bendertest::RunInProcess({ "clip", Aneurysm, "-o", Aneurysm });
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.err.find("refusing to overwrite"), std::string::npos) << run.err;
  // A missing input.
  run = bendertest::RunInProcess({ "clip", Temp("missing.stl"), "-o", out });
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(Lines(run.err), 1) << run.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  // --help.
  run = bendertest::RunInProcess({ "clip", "--help" });
  EXPECT_EQ(run.status, 0);
  EXPECT_NE(run.out.find("usage: bender-cli clip"), std::string::npos);
}

TEST(CliClip, AnEndItCannotClipIsRefusedAndNothingIsWritten)
{
  // A tube with a branch 1.2 mm wide open at x = 20, and centerlines of the tube only.
  const std::vector<bender::test::Segment> tubes = { { { { 0, 0, -40 } }, { { 0, 0, 40 } }, 3.013 },
    { { { 0, 0, 0 } }, { { 40, 0, 0 } }, 0.6013 } };
  const double bounds[6] = { -5, 20, -4.2, 4.2, -20, 20 };
  const std::string surface = Temp("branched.vtp"), centerlines = Temp("trunk.vtp");
  const std::string out = Temp("branched-cfd.vtp");
  bender::WriteMesh(bender::test::ImplicitTubes(tubes, bounds, 0.2), surface);
  bender::CenterlineOptions trunk;
  trunk.seeds = { { { 0, 0, -20 } }, { { 0, 0, 20 } } };
  bender::WriteMesh(
    bender::ComputeCenterlines(bender::ReadMesh(surface), trunk).paths, centerlines);
  std::filesystem::remove(out);
  bendertest::CliRun run =
    bendertest::RunInProcess({ "clip", surface, "-o", out, "--centerlines", centerlines });
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(Lines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find("(20, 0, 0) (1.2 mm wide) would not be clipped"), std::string::npos)
    << run.err;
  EXPECT_NE(run.err.find("centerlines through it"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  // At the branch's tip with DIST: the nearest end is the tube's, whose vessel is far.
  run = bendertest::RunInProcess(
    { "clip", surface, "-o", out, "--centerlines", centerlines, "--end", "19.5,0,0:2" });
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(Lines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find("mm from the vessel of the nearest end"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  // As told: the centerlines computed, through every end.
  run = bendertest::RunInProcess({ "clip", surface, "-o", out });
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("3 ends"), std::string::npos) << run.out;
  EXPECT_EQ(bender::ReadPatchLabels(bender::ReadMesh(out)).size(), 4u);
  for (const std::string& f : { surface, centerlines, out })
  {
    std::filesystem::remove(f);
  }
}
