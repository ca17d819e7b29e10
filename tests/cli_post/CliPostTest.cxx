// bender-cli check | export | warp (with subdivision) end to end: the real executable on
// real files.

#include "CliPostTestUtilities.h"

#include "MeshIO.h"
#include "PatchLabels.h"

#include <nlohmann/json.hpp>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <fstream>

using namespace clitest;

namespace
{
// A closed, consistently oriented octahedron (outward normals).
const char* const Octahedron = "OFF\n6 8 0\n"
                               "1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n"
                               "3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n"
                               "3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n";

// Three triangles on one edge: non-manifold.
const char* const NonManifold = "OFF\n5 3 0\n"
                                "0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n"
                                "3 0 1 2\n3 1 0 3\n3 0 1 4\n";

void WriteText(const std::string& path, const std::string& text)
{
  std::ofstream(path, std::ios::binary) << text;
}

// The octahedron with vertex 4 pushed through to z = -2: the four top triangles flip.
const char* const OctahedronFolded = "OFF\n6 8 0\n"
                                     "1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 -2\n0 0 -1\n"
                                     "3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n"
                                     "3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n";
} // namespace

// --- check ----------------------------------------------------------------------------------

class CliCheck : public ScratchTest
{
};

TEST_F(CliCheck, CleanMeshExitsZero)
{
  WriteText(Tmp("octa.off"), Octahedron);
  const Result r = Run("check " + Q(Tmp("octa.off")) + " --closed");
  EXPECT_EQ(r.status, 0) << r.output << r.errors;
  EXPECT_NE(r.output.find("closed"), std::string::npos) << r.output;
}

TEST_F(CliCheck, ProblemsExitOne)
{
  WriteText(Tmp("bad.off"), NonManifold);
  Result r = Run("check " + Q(Tmp("bad.off")));
  EXPECT_EQ(r.status, 1) << r.output << r.errors;
  EXPECT_NE(r.output.find("non-manifold"), std::string::npos) << r.output;
  // An open surface is clean unless --closed asks for a watertight one.
  WriteText(Tmp("open.off"), "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(Run("check " + Q(Tmp("open.off"))).status, 0);
  EXPECT_EQ(Run("check " + Q(Tmp("open.off")) + " --closed").status, 1);
}

TEST_F(CliCheck, UnreadableExitsTwo)
{
  Result r = Run("check " + Q(Data + "/cli/truncated.stl"));
  EXPECT_EQ(r.status, 2) << r.output << r.errors;
  EXPECT_NE(r.errors.find("truncated.stl"), std::string::npos) << r.errors;
  // A missing file is unreadable input, said in the reader's words as by every command (not
  // a usage error): exit 2 as for every mesh check cannot read (its 1 is "problems found").
  r = Run("check " + Q(Tmp("missing.off")));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.errors.find("bender-cli check: missing.off: no such file"), std::string::npos)
    << r.errors;
  EXPECT_EQ(r.errors.find("--help"), std::string::npos) << r.errors;
  const Result measure = Run("measure " + Q(Tmp("missing.off")));
  EXPECT_NE(measure.errors.find("bender-cli measure: missing.off: no such file"), std::string::npos)
    << measure.errors;
  WriteText(Tmp("octa.off"), Octahedron);
  r = Run("check " + Q(Tmp("octa.off")) + " --before " + Q(Tmp("missing.off")));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.errors.find("bender-cli check: missing.off: no such file"), std::string::npos)
    << r.errors;
  EXPECT_EQ(Run("check").status, 2);
  EXPECT_EQ(Run("check a.off --no-such-option").status, 2);
}

TEST_F(CliCheck, JsonParses)
{
  WriteText(Tmp("octa.off"), Octahedron);
  WriteText(Tmp("bad.off"), NonManifold);
  Result r = Run("check " + Q(Tmp("octa.off")) + " --json");
  ASSERT_EQ(r.status, 0) << r.errors;
  const auto clean = nlohmann::json::parse(r.output);
  EXPECT_EQ(clean.at("clean"), true);
  EXPECT_EQ(clean.at("triangles"), 8);
  EXPECT_EQ(clean.at("closed"), true);
  EXPECT_TRUE(clean.at("boundaryLoops").empty());
  EXPECT_NEAR(clean.at("volume").get<double>(), 4.0 / 3.0, 1e-6);
  EXPECT_TRUE(clean.at("problems").empty());
  r = Run("check " + Q(Tmp("bad.off")) + " --json");
  ASSERT_EQ(r.status, 1) << r.errors;
  const auto bad = nlohmann::json::parse(r.output);
  EXPECT_EQ(bad.at("clean"), false);
  EXPECT_EQ(bad.at("nonManifoldEdges"), 1);
  EXPECT_FALSE(bad.at("problems").empty());
}

TEST_F(CliCheck, BeforeReportsFlips)
{
  WriteText(Tmp("octa.off"), Octahedron);
  WriteText(Tmp("folded.off"), OctahedronFolded);
  Result r = Run("check " + Q(Tmp("folded.off")) + " --before " + Q(Tmp("octa.off")) + " --json");
  EXPECT_EQ(r.status, 1) << r.errors;
  const auto folded = nlohmann::json::parse(r.output);
  // The 4 inverted triangles, and possibly their partners across the fold.
  EXPECT_GE(folded.at("flippedTriangles").get<int>(), 4);
  EXPECT_LE(folded.at("flippedTriangles").get<int>(), 8);
  r = Run("check " + Q(Tmp("octa.off")) + " --before " + Q(Tmp("octa.off")) + " --json");
  EXPECT_EQ(r.status, 0) << r.errors;
  EXPECT_EQ(nlohmann::json::parse(r.output).at("flippedTriangles"), 0);
}

// --- export ---------------------------------------------------------------------------------

class CliExport : public ScratchTest
{
};

TEST_F(CliExport, CapsTheAneurysmIntoAClosedSurface)
{
  REQUIRE_FILE(External + "/aneurysm_data.stl");
  Result r = Run(
    "export " + Q(External + "/aneurysm_data.stl") + " -o " + Q(Tmp("a.stl")) + " --cap --quiet");
  ASSERT_EQ(r.status, 0) << r.errors;
  r = Run("check " + Q(Tmp("a.stl")) + " --closed --json");
  EXPECT_EQ(r.status, 0) << r.output;
  const auto report = nlohmann::json::parse(r.output);
  EXPECT_EQ(report.at("closed"), true);
  EXPECT_GT(report.at("volume").get<double>(), 0.0);
  // The VTK form keeps the labels: wall 0 and three caps.
  ASSERT_EQ(Run("export " + Q(External + "/aneurysm_data.stl") + " -o " + Q(Tmp("a.vtp")) +
              " --cap --quiet")
              .status,
    0);
  const auto mesh = bender::ReadMesh(Tmp("a.vtp"));
  ASSERT_TRUE(bender::HasPatchLabels(mesh));
  const std::vector<int> ids = bender::CellPatchIds(mesh);
  EXPECT_EQ(*std::min_element(ids.begin(), ids.end()), bender::kWallEntityId);
  EXPECT_EQ(*std::max_element(ids.begin(), ids.end()), 4); // wall 1, three ends 2..4
  EXPECT_EQ(bender::ReadPatchLabels(mesh).size(), 4u);
}

TEST_F(CliExport, SolidsAreNamedWallAndCaps)
{
  REQUIRE_FILE(External + "/aneurysm_data.stl");
  const Result r = Run("export " + Q(External + "/aneurysm_data.stl") + " -o " + Q(Tmp("a.stl")) +
    " --cap --patches solids --quiet");
  ASSERT_EQ(r.status, 0) << r.errors;
  const std::string text = ReadText(Tmp("a.stl"));
  // One solid per patch, named as the sidecar names them: the wall and three ends.
  const auto sidecar = nlohmann::json::parse(ReadText(Tmp("a.patches.json")));
  ASSERT_EQ(sidecar.at("patches").size(), 4u);
  EXPECT_EQ(sidecar.at("patches")[0].at("name"), "wall");
  for (const auto& patch : sidecar.at("patches"))
  {
    const std::string solid = "solid " + patch.at("name").get<std::string>() + "\n";
    EXPECT_NE(text.find(solid), std::string::npos) << solid;
  }
  std::size_t solids = 0;
  for (std::size_t at = text.find("solid "); at != std::string::npos;
       at = text.find("solid ", at + 1))
  {
    solids += (at == 0 || text[at - 1] == '\n') ? 1 : 0;
  }
  EXPECT_EQ(solids, 4u);
  EXPECT_NE(text.find("frame LPS, unit mm"), std::string::npos);
  // The multi-solid file reads back as one closed surface.
  EXPECT_EQ(Run("check " + Q(Tmp("a.stl")) + " --closed").status, 0);
}

TEST_F(CliExport, FilesModeWritesOneFilePerPatch)
{
  REQUIRE_FILE(External + "/aneurysm_data.stl");
  const Result r = Run("export " + Q(External + "/aneurysm_data.stl") + " -o " + Q(Tmp("a.stl")) +
    " --cap --patches files --quiet");
  ASSERT_EQ(r.status, 0) << r.errors;
  // One file per patch named by it (wall and three ends), and the sidecar.
  const std::vector<std::string> files = Files();
  ASSERT_EQ(files.size(), 5u);
  EXPECT_EQ(std::count(files.begin(), files.end(), "a.patches.json"), 1);
  EXPECT_EQ(std::count(files.begin(), files.end(), "a_wall.stl"), 1);
  const auto sidecar = nlohmann::json::parse(ReadText(Tmp("a.patches.json")));
  ASSERT_EQ(sidecar.at("patches").size(), 4u);
  for (const auto& patch : sidecar.at("patches"))
  {
    const std::string name = "a_" + patch.at("name").get<std::string>() + ".stl";
    EXPECT_EQ(std::count(files.begin(), files.end(), name), 1) << name;
    EXPECT_GT(bender::ReadMesh(Tmp(name))->GetNumberOfPolys(), 0) << name;
  }
}

TEST_F(CliExport, FrameIsStatedRasNegatesXAndYAndReadsBackInLps)
{
  WriteText(Tmp("octa.off"), Octahedron);
  WriteText(Tmp("shifted.off"), "OFF\n3 1 0\n10 20 30\n11 20 30\n10 21 30\n3 0 1 2\n");
  ASSERT_EQ(
    Run("export " + Q(Tmp("shifted.off")) + " -o " + Q(Tmp("lps.stl")) + " --quiet").status, 0);
  ASSERT_EQ(
    Run("export " + Q(Tmp("shifted.off")) + " -o " + Q(Tmp("ras.stl")) + " --frame ras --quiet")
      .status,
    0);
  EXPECT_EQ(
    ReadText(Tmp("lps.stl")).substr(0, 80).find("frame LPS, unit mm") == std::string::npos, false);
  EXPECT_EQ(
    ReadText(Tmp("ras.stl")).substr(0, 80).find("frame RAS, unit mm") == std::string::npos, false);
  // The file holds the first vertex with x and y negated (after the header, the triangle
  // count and the normal)...
  std::ifstream file(Tmp("ras.stl"), std::ios::binary);
  float vertex[3];
  file.seekg(80 + 4 + 12);
  file.read(reinterpret_cast<char*>(vertex), sizeof vertex);
  EXPECT_FLOAT_EQ(vertex[0], -10.0f);
  EXPECT_FLOAT_EQ(vertex[1], -20.0f);
  EXPECT_FLOAT_EQ(vertex[2], 30.0f);
  // ... and reads back in LPS, where the LPS export is.
  const auto lps = bender::ReadMesh(Tmp("lps.stl"));
  const auto ras = bender::ReadMesh(Tmp("ras.stl"));
  ASSERT_EQ(lps->GetNumberOfPoints(), ras->GetNumberOfPoints());
  double lo[6], ro[6];
  lps->GetBounds(lo);
  ras->GetBounds(ro);
  for (int k = 0; k < 6; ++k)
  {
    EXPECT_DOUBLE_EQ(ro[k], lo[k]) << k;
  }
  EXPECT_DOUBLE_EQ(lo[0], 10.0);
  EXPECT_EQ(
    Run("export " + Q(Tmp("octa.off")) + " -o " + Q(Tmp("x.stl")) + " --frame xyz").status, 2);
}

TEST_F(CliExport, NeverOverwritesTheInput)
{
  ASSERT_EQ(
    Run("export " + Q(Data + "/io/tetra_ascii.stl") + " -o " + Q(Tmp("t.stl")) + " --quiet").status,
    0);
  const std::string before = ReadText(Tmp("t.stl"));
  const Result r = Run("export " + Q(Tmp("t.stl")) + " -o " + Q(Tmp("t.stl")));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.errors.find("t.stl"), std::string::npos) << r.errors;
  EXPECT_EQ(ReadText(Tmp("t.stl")), before);
  // The same file through another path.
  EXPECT_NE(Run("export " + Q(Tmp("t.stl")) + " -o " + Q(Tmp("./t.stl"))).status, 0);
  EXPECT_EQ(ReadText(Tmp("t.stl")), before);
  // One file per patch: OUT_wall.stl must not be the input either.
  ASSERT_EQ(
    Run("export " + Q(Tmp("t.stl")) + " -o " + Q(Tmp("v_wall.stl")) + " --quiet").status, 0);
  const std::string wall = ReadText(Tmp("v_wall.stl"));
  const Result files =
    Run("export " + Q(Tmp("v_wall.stl")) + " -o " + Q(Tmp("v.stl")) + " --patches files");
  EXPECT_EQ(files.status, 1) << files.errors;
  EXPECT_NE(files.errors.find("overwrite"), std::string::npos) << files.errors;
  EXPECT_EQ(ReadText(Tmp("v_wall.stl")), wall);
}

TEST_F(CliExport, AtomicNoTemporaryLeftOnFailure)
{
  // Points but no triangles: nothing can be exported.
  WriteText(Tmp("points.off"), "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n");
  const std::vector<std::string> before = Files();
  Result r = Run("export " + Q(Tmp("points.off")) + " -o " + Q(Tmp("out.stl")));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_EQ(Files(), before);
  // Unreadable input, then a missing output folder.
  r = Run("export " + Q(Data + "/cli/truncated.stl") + " -o " + Q(Tmp("out.stl")));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(Files(), before);
  WriteText(Tmp("octa.off"), Octahedron);
  const std::vector<std::string> withOcta = Files();
  r = Run("export " + Q(Tmp("octa.off")) + " -o " + Q(Tmp("no/such/folder/out.stl")));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(Files(), withOcta);
  // Files mode that fails on the folder leaves no partial set.
  r = Run("export " + Q(Tmp("octa.off")) + " -o " + Q(Tmp("no/out.stl")) + " --patches files");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(Files(), withOcta);
}

// --- warp with subdivision --------------------------------------------------------------------

class CliWarpSubdivision : public ScratchTest
{
};

TEST_F(CliWarpSubdivision, PlanSubdivisionRefinesAndStaysClean)
{
  REQUIRE_FILE(External + "/plane.off");
  const std::string plan = Examples + "fig13-plane-bowl.bender.json";
  const Result r =
    Run("warp " + Q(External + "/plane.off") + " " + Q(plan) + " " + Q(Tmp("bowl.vtp")));
  ASSERT_EQ(r.status, 0) << r.errors;
  EXPECT_NE(r.output.find("subdivision"), std::string::npos) << r.output;
  const auto in = bender::ReadMesh(External + "/plane.off");
  const auto out = bender::ReadMesh(Tmp("bowl.vtp"));
  EXPECT_GT(out->GetNumberOfPolys(), in->GetNumberOfPolys());
  const Result check = Run("check " + Q(Tmp("bowl.vtp")) + " --json");
  EXPECT_EQ(check.status, 0) << check.output;
  const auto report = nlohmann::json::parse(check.output);
  EXPECT_EQ(report.at("boundaryLoops").size(), 1u);
  EXPECT_EQ(report.at("nonManifoldEdges"), 0);
  // The bottom of the bowl went down by the wire's 0.3 drop.
  double b[6];
  out->GetBounds(b);
  EXPECT_NEAR(b[2], -0.3, 1e-6);
  // --before cannot pair the triangles after subdivision: it says so instead of guessing.
  const Result flips =
    Run("check " + Q(Tmp("bowl.vtp")) + " --before " + Q(External + "/plane.off") + " --json");
  EXPECT_EQ(nlohmann::json::parse(flips.output).at("flippedTriangles"), nullptr);
}
