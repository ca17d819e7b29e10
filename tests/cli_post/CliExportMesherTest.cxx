// bender-cli export for CFD meshers (issue 11): --unit, named solids, .vtp labels, TetGen
// .smesh, the patches sidecar and the refusals, through the real executable.

#include "CliPostTestUtilities.h"
#include "MeshIO.h"
#include "PatchLabels.h"

#include "../IO/MesherTestUtilities.h"

#include <nlohmann/json.hpp>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

using namespace clitest;

namespace
{
class CliMesherExport : public ScratchTest
{
protected:
  void SetUp() override
  {
    ScratchTest::SetUp();
    this->Input = Tmp("vessel.vtp");
    bender::WriteMesh(bender_test::LabelledCylinder(), this->Input);
  }
  std::string Input;
};

std::string FieldString(vtkPolyData* mesh, const char* name)
{
  auto* array = vtkStringArray::SafeDownCast(mesh->GetFieldData()->GetAbstractArray(name));
  return array && array->GetNumberOfValues() > 0 ? array->GetValue(0) : std::string();
}
} // namespace

TEST_F(CliMesherExport, NamedSolidsInMetresWithTheSidecar)
{
  const Result r =
    Run("export " + Q(Input) + " -o " + Q(Tmp("v.stl")) + " --patches solids --unit m");
  ASSERT_EQ(r.status, 0) << r.errors;
  EXPECT_NE(r.output.find("patches: wall (wall, 1), inlet (inlet, 2), outlet_1 (outlet, 3)"),
    std::string::npos)
    << r.output;
  EXPECT_NE(r.output.find("inside point:"), std::string::npos) << r.output;
  const std::string text = ReadText(Tmp("v.stl"));
  for (const char* solid : { "solid wall\n", "solid inlet\n", "solid outlet_1\n" })
  {
    EXPECT_NE(text.find(solid), std::string::npos) << solid;
  }
  EXPECT_NE(text.find("frame LPS, unit m\n"), std::string::npos);
  // Metres: the 10 mm vessel is 0.01 long in the file...
  double topZ = -HUGE_VAL;
  std::istringstream lines(text);
  for (std::string word; lines >> word;)
  {
    double x, y, z;
    if (word == "vertex" && lines >> x >> y >> z)
    {
      topZ = std::max(topZ, z);
    }
  }
  EXPECT_NEAR(topZ, 0.01, 1e-8);
  // ... and read back in millimetres, as the file says.
  bender::StatedSpace stated;
  const auto back = bender::ReadMesh(Tmp("v.stl"), stated);
  EXPECT_EQ(stated.unit, "m");
  EXPECT_EQ(stated.frame, "LPS");
  double bounds[6];
  back->GetBounds(bounds);
  EXPECT_NEAR(bounds[5] - bounds[4], 10.0, 1e-5);
  EXPECT_NEAR(bounds[1], 101.0, 1e-5);
  // The sidecar, always written with patches.
  const auto sidecar = nlohmann::json::parse(ReadText(Tmp("v.patches.json")));
  EXPECT_EQ(sidecar.at("unit"), "m");
  EXPECT_EQ(sidecar.at("frame"), "LPS");
  ASSERT_EQ(sidecar.at("patches").size(), 3u);
  EXPECT_EQ(sidecar.at("patches")[2].at("name"), "outlet_1");
  EXPECT_EQ(sidecar.at("patches")[2].at("type"), "outlet");
  EXPECT_NEAR(sidecar.at("patches")[2].at("area").get<double>(), M_PI * 1e-6, 0.01 * M_PI * 1e-6);
  EXPECT_NEAR(sidecar.at("patches")[2].at("normal")[2].get<double>(), 1.0, 1e-9);
  const auto inside = sidecar.at("insidePoint");
  ASSERT_EQ(inside.size(), 3u);
  const double dx = inside[0].get<double>() - 0.1, dy = inside[1].get<double>();
  EXPECT_LT(std::hypot(dx, dy), 0.001); // within the 1 mm radius
  EXPECT_GT(inside[2].get<double>(), 0.0);
  EXPECT_LT(inside[2].get<double>(), 0.01);
}

TEST_F(CliMesherExport, VtpKeepsLabelsNamesUnitAndFrame)
{
  const Result r =
    Run("export " + Q(Input) + " -o " + Q(Tmp("v.vtp")) + " --unit m --frame ras --quiet");
  ASSERT_EQ(r.status, 0) << r.errors;
  EXPECT_EQ(r.output, "");
  EXPECT_FALSE(std::filesystem::exists(Tmp("v.patches.json"))); // not asked for
  bender::StatedSpace stated;
  const auto back = bender::ReadMesh(Tmp("v.vtp"), stated);
  const auto original = bender::ReadMesh(Input);
  EXPECT_EQ(bender::CellPatchIds(back), bender::CellPatchIds(original));
  ASSERT_NE(back->GetCellData()->GetArray(bender::kModelFaceIdArrayName), nullptr);
  const auto labels = bender::ReadPatchLabels(back);
  ASSERT_EQ(labels.size(), 3u);
  EXPECT_EQ(labels[1].name, "inlet");
  EXPECT_EQ(labels[1].type, bender::PatchType::Inlet);
  // The file states RAS metres; read back in LPS millimetres (its fields now say so), where
  // the original's points are.
  EXPECT_EQ(stated.unit, "m");
  EXPECT_EQ(stated.frame, "RAS");
  EXPECT_EQ(FieldString(back, "Unit"), "mm");
  EXPECT_EQ(FieldString(back, "Frame"), "LPS");
  for (const vtkIdType id : { vtkIdType(0), vtkIdType(7), original->GetNumberOfPoints() - 1 })
  {
    double p[3], q[3];
    original->GetPoint(id, p);
    back->GetPoint(id, q);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(q[c], p[c], 1e-12 * (1 + std::abs(p[c]))) << id;
    }
  }
}

TEST_F(CliMesherExport, SmeshHasEveryMarkerAndTheSidecar)
{
  const Result r = Run("export " + Q(Input) + " -o " + Q(Tmp("v.smesh")) + " --unit m --quiet");
  ASSERT_EQ(r.status, 0) << r.errors;
  EXPECT_TRUE(std::filesystem::exists(Tmp("v.patches.json")));
  std::istringstream in(ReadText(Tmp("v.smesh")));
  std::string line;
  std::vector<std::string> data;
  while (std::getline(in, line))
  {
    if (!line.empty() && line[0] != '#')
    {
      data.push_back(line);
    }
  }
  ASSERT_FALSE(data.empty());
  long long nodes = 0;
  std::istringstream(data[0]) >> nodes;
  ASSERT_LT(static_cast<std::size_t>(nodes) + 1, data.size());
  long long facets = 0;
  std::istringstream(data[static_cast<std::size_t>(nodes) + 1]) >> facets;
  EXPECT_EQ(facets, bender_test::LabelledCylinder()->GetNumberOfCells());
  std::map<int, int> markers;
  for (long long f = 0; f < facets; ++f)
  {
    int corners, a, b, c, marker;
    std::istringstream(data.at(static_cast<std::size_t>(nodes + 2 + f))) >> corners >> a >> b >>
      c >> marker;
    ++markers[marker];
  }
  EXPECT_EQ(markers.size(), 3u);
  EXPECT_EQ(markers[2], bender_test::Segments);
}

TEST_F(CliMesherExport, CheckReadsTheSmeshAndPolyItWrote)
{
  // The same surface as its source, in millimetres (the files say unit m).
  const nlohmann::json source = nlohmann::json::parse(Run("check " + Q(Input) + " --json").output);
  for (const char* name : { "v.smesh", "v.poly" })
  {
    ASSERT_EQ(Run("export " + Q(Input) + " -o " + Q(Tmp(name)) + " --unit m --quiet").status, 0);
    const Result r = Run("check " + Q(Tmp(name)) + " --json");
    ASSERT_NE(r.status, 2) << r.errors;
    const nlohmann::json report = nlohmann::json::parse(r.output);
    EXPECT_EQ(report.at("triangles"), source.at("triangles")) << name;
    EXPECT_NEAR(report.at("area").get<double>(),
      source.at("area").get<double>(),
      1e-6 * source.at("area").get<double>())
      << name;
  }
}

TEST_F(CliMesherExport, PolyAndTheSidecarOnRequest)
{
  // A single binary STL writes the sidecar only when asked.
  Result r = Run("export " + Q(Input) + " -o " + Q(Tmp("s.stl")) + " --quiet");
  ASSERT_EQ(r.status, 0) << r.errors;
  EXPECT_FALSE(std::filesystem::exists(Tmp("s.patches.json")));
  r = Run("export " + Q(Input) + " -o " + Q(Tmp("j.stl")) + " --patches-json --quiet");
  ASSERT_EQ(r.status, 0) << r.errors;
  const auto sidecar = nlohmann::json::parse(ReadText(Tmp("j.patches.json")));
  EXPECT_EQ(sidecar.at("unit"), "mm");
  EXPECT_NEAR(sidecar.at("patches")[1].at("equivalentDiameter").get<double>(), 2.0, 0.01);
  // TetGen .poly: one polygon per facet, with its marker.
  r = Run("export " + Q(Input) + " -o " + Q(Tmp("v.poly")) + " --quiet");
  ASSERT_EQ(r.status, 0) << r.errors;
  const std::string poly = ReadText(Tmp("v.poly"));
  EXPECT_NE(poly.find("TetGen .poly"), std::string::npos);
  EXPECT_NE(poly.find("\n1 0 3\n3 "), std::string::npos); // a facet of the outlet
  EXPECT_TRUE(std::filesystem::exists(Tmp("v.patches.json")));
}

TEST_F(CliMesherExport, RefusesWhatCannotBeWritten)
{
  // --cap on a closed surface without labelled ends: nothing to cap, nothing written.
  std::ofstream(Tmp("octa.off")) << "OFF\n6 8 0\n"
                                    "1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n"
                                    "3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n"
                                    "3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n";
  Result r =
    Run("export " + Q(Tmp("octa.off")) + " -o " + Q(Tmp("o.stl")) + " --cap --patches solids");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(
    r.errors.find("octa.off: nothing to cap: the surface has no open end"), std::string::npos)
    << r.errors;
  EXPECT_FALSE(std::filesystem::exists(Tmp("o.stl")));
  EXPECT_FALSE(std::filesystem::exists(Tmp("o.patches.json")));
  // A labelled surface is already capped: --cap keeps its ends.
  r = Run("export " + Q(Input) + " -o " + Q(Tmp("c.stl")) + " --cap --patches solids --quiet");
  EXPECT_EQ(r.status, 0) << r.errors;
  EXPECT_NE(ReadText(Tmp("c.stl")).find("solid inlet\n"), std::string::npos);
  // Usage errors.
  for (const std::string& args : { " -o " + Q(Tmp("x.stl")) + " --unit cm",
         " -o " + Q(Tmp("x.vtp")) + " --patches files",
         " -o " + Q(Tmp("x.smesh")) + " --patches solids",
         " -o " + Q(Tmp("x.xyz")) })
  {
    r = Run("export " + Q(Input) + args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.errors;
  }
  EXPECT_FALSE(std::filesystem::exists(Tmp("x.stl")));
  EXPECT_FALSE(std::filesystem::exists(Tmp("x.vtp")));
}
