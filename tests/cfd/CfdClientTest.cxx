// The real clients of a CFD-ready vessel (issue 11): OpenFOAM (surfaceCheck, blockMesh,
// snappyHexMesh, checkMesh, simpleFoam), TetGen and gmsh, on the gmsh aneurysm capped with
// labelled ends and on the segmented demo vessel prepared by PrepareForCfd (clipped, extended,
// capped), each original and bent by the demo plan. Label `cfd`. Coarse meshes and 50
// iterations keep each case to a few tens of seconds; the times are printed, not asserted.

#include "CfdCase.h"
#include "CfdTestUtilities.h"
#include "ExportSurface.h"
#include "PatchLabels.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace fs = std::filesystem;
using bender::test::RunIn;

namespace
{

struct ClientCase
{
  const char* name;
  bool bent;
  int processors;     ///< the bent aneurysm also checks the parallel path (mpirun -np 2)
  bool segmented;     ///< the segmented demo vessel prepared by PrepareForCfd, else the aneurysm
  double cellsAcross; ///< wall cells across the smallest end
};

vtkSmartPointer<vtkPolyData> Surface(const ClientCase& c)
{
  return c.segmented ? bender::test::PreparedDemoVessel(c.bent)
                     : bender::test::CappedAneurysm(c.bent);
}

std::ostream& operator<<(std::ostream& os, const ClientCase& c)
{
  return os << c.name;
}

class CfdClient : public ::testing::TestWithParam<ClientCase>
{
};

double Seconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

/// OpenFOAM's programs need WM_PROJECT_DIR; Debian's package keeps etc/ there.
const char* const FoamEnv = "WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam} ";

/// Triangle counts per region of surfaceCheck's "Region Size" table.
std::map<std::string, long long> SurfaceCheckRegions(const std::string& output)
{
  std::map<std::string, long long> regions;
  std::istringstream lines(output);
  std::string line;
  bool inTable = false;
  while (std::getline(lines, line))
  {
    if (line.rfind("Region", 0) == 0)
    {
      inTable = true;
      continue;
    }
    if (!inTable || line.rfind("------", 0) == 0)
    {
      continue;
    }
    std::istringstream words(line);
    std::string name;
    long long size = -1;
    if (!(words >> name >> size))
    {
      break;
    }
    regions[name] = size;
  }
  return regions;
}

TEST_P(CfdClient, OpenFoamMeshesTheNamedPatchesAndConservesMass)
{
  for (const char* program : { "surfaceCheck",
         "blockMesh",
         "surfaceFeatureExtract",
         "snappyHexMesh",
         "checkMesh",
         "simpleFoam" })
  {
    BENDER_REQUIRE_PROGRAM(program);
  }
  if (GetParam().processors > 1)
  {
    for (const char* program : { "decomposePar", "reconstructPar", "mpirun" })
    {
      BENDER_REQUIRE_PROGRAM(program);
    }
  }
  const auto surface = Surface(GetParam());
  const std::vector<bender::PatchLabel> labels = bender::ReadPatchLabels(surface);
  ASSERT_GE(labels.size(), 4u);
  bender::test::TemporaryFolder folder("cfd-openfoam");

  // A coarse mesh: a few wall cells across the smallest end.
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  options.sourceName = GetParam().name;
  options.iterations = 50;
  options.processors = GetParam().processors;
  const bender::CfdCaseResult probe = bender::WriteOpenFoamCase(surface, options);
  double smallest = 1.0;
  for (const auto& p : probe.patches)
  {
    if (p.type != bender::PatchType::Wall)
    {
      smallest = std::min(smallest, p.diameter);
    }
  }
  options.cellSize = smallest / GetParam().cellsAcross;
  options.force = true;
  const bender::CfdCaseResult written = bender::WriteOpenFoamCase(surface, options);
  EXPECT_EQ(written.inlet, "inlet");

  // surfaceCheck: one closed surface with the named regions, triangles as labelled.
  auto start = std::chrono::steady_clock::now();
  int status = 0;
  const std::string check = RunIn(options.caseDirectory,
    std::string(FoamEnv) + "surfaceCheck constant/triSurface/vessel.stl",
    status);
  std::printf("[ timing ] %s surfaceCheck %.1f s\n", GetParam().name, Seconds(start));
  ASSERT_EQ(status, 0) << check;
  EXPECT_NE(check.find("Surface is closed. All edges connected to two faces."), std::string::npos)
    << check;
  EXPECT_NE(check.find("Number of unconnected parts : 1\n"), std::string::npos) << check;
  const auto regions = SurfaceCheckRegions(check);
  ASSERT_EQ(regions.size(), written.patches.size()) << check;
  for (const auto& p : written.patches)
  {
    ASSERT_EQ(regions.count(p.name), 1u) << p.name << "\n" << check;
    EXPECT_EQ(regions.at(p.name), p.triangles) << p.name;
  }

  // blockMesh, surfaceFeatureExtract, snappyHexMesh, checkMesh: "Mesh OK", every patch there.
  start = std::chrono::steady_clock::now();
  bender::CfdRunOptions mesh;
  mesh.steps = bender::CfdRunOptions::Steps::Mesh;
  ASSERT_NO_THROW(bender::RunOpenFoamCase(options.caseDirectory, mesh))
    << bender::test::ReadText(options.caseDirectory + "/log.Allrun");
  std::printf("[ timing ] %s mesh (blockMesh + snappyHexMesh + checkMesh) %.1f s\n",
    GetParam().name,
    Seconds(start));
  const std::string checkMesh = bender::test::ReadText(options.caseDirectory + "/log.checkMesh");
  EXPECT_NE(checkMesh.find("\nMesh OK."), std::string::npos) << checkMesh;
  const auto meshPatches = bender::ReadMeshPatches(options.caseDirectory);
  for (const auto& p : written.patches)
  {
    bool found = false;
    for (const auto& [name, faces] : meshPatches)
    {
      if (name == p.name)
      {
        found = true;
        EXPECT_GT(faces, 0) << p.name;
      }
    }
    EXPECT_TRUE(found) << p.name << " is not a patch of the mesh";
  }
  const std::string boundary =
    bender::test::ReadText(options.caseDirectory + "/constant/polyMesh/boundary");
  EXPECT_NE(boundary.find("wall\n    {\n        type            wall;"), std::string::npos)
    << boundary;
  EXPECT_NE(boundary.find("inlet\n    {\n        type            patch;"), std::string::npos)
    << boundary;

  // 50 iterations of simpleFoam: the flow leaves through the outlets, mass conserved to 1 %.
  start = std::chrono::steady_clock::now();
  bender::CfdRunOptions solve;
  solve.steps = bender::CfdRunOptions::Steps::Solve;
  bender::CfdRunResult run;
  ASSERT_NO_THROW(run = bender::RunOpenFoamCase(options.caseDirectory, solve))
    << bender::test::ReadText(options.caseDirectory + "/log.Allrun");
  std::printf("[ timing ] %s simpleFoam 50 iterations on %d processor(s) %.1f s\n",
    GetParam().name,
    options.processors,
    Seconds(start));
  std::printf("%s", bender::FormatCfdRun(run).c_str());
  EXPECT_TRUE(run.iterations == 50 || run.converged) << run.iterations;
  EXPECT_LT(run.massImbalance, 0.01);
  // The inlet's flux is the velocity times the snapped inlet's area (coarse: within 15 %).
  EXPECT_NEAR(run.inletFlowRate, written.inletFlowRate, 0.15 * written.inletFlowRate);
  double percent = 0.0;
  int outlets = 0;
  for (const auto& f : run.patches)
  {
    if (f.type == bender::PatchType::Outlet)
    {
      ++outlets;
      percent += f.percentOfInlet;
      EXPECT_GT(f.flowRate, 0.0) << f.name;
      EXPECT_GT(f.pressureDrop, 0.0) << f.name;
      EXPECT_NEAR(f.pressure, 0.0, 1e-9) << f.name << " is at p = 0";
    }
  }
  EXPECT_EQ(outlets, static_cast<int>(labels.size()) - 2);
  EXPECT_NEAR(percent, 100.0, 1.0);
  std::set<std::string> fields;
  for (const auto& [field, value] : run.residuals)
  {
    fields.insert(field);
    EXPECT_GT(value, 0.0) << field;
    EXPECT_LT(value, 1.0) << field;
  }
  EXPECT_EQ(fields, (std::set<std::string>{ "Ux", "Uy", "Uz", "p" }));
  if (options.processors > 1)
  {
    EXPECT_TRUE(fs::exists(options.caseDirectory + "/processor1"));
    EXPECT_TRUE(fs::exists(options.caseDirectory + "/log.reconstructPar"));
  }
}

TEST_P(CfdClient, TetgenKeepsEveryMarker)
{
  BENDER_REQUIRE_PROGRAM("tetgen");
  const auto surface = Surface(GetParam());
  const std::vector<bender::PatchLabel> labels = bender::ReadPatchLabels(surface);
  bender::test::TemporaryFolder folder("cfd-tetgen");
  bender::ExportSurfaceOptions options;
  options.output = folder.Path() + "/vessel.smesh";
  options.unit = "m";
  bender::ExportSurface(surface, options);
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  const std::string output = RunIn(folder.Path(), "tetgen -pq vessel.smesh", status);
  std::printf("[ timing ] %s tetgen -pq %.1f s\n", GetParam().name, Seconds(start));
  ASSERT_EQ(status, 0) << output;
  // vessel.1.face: "N 1" then "i a b c marker" per boundary face.
  std::ifstream faces(folder.Path() + "/vessel.1.face");
  ASSERT_TRUE(faces) << output;
  long long count = 0, hasMarkers = 0;
  faces >> count >> hasMarkers;
  ASSERT_GT(count, 0);
  ASSERT_EQ(hasMarkers, 1);
  std::map<int, long long> perMarker;
  for (long long i = 0; i < count; ++i)
  {
    long long index, a, b, c;
    int marker;
    ASSERT_TRUE(faces >> index >> a >> b >> c >> marker) << "face " << i;
    ++perMarker[marker];
  }
  std::set<int> markers, expected;
  for (const auto& [marker, n] : perMarker)
  {
    markers.insert(marker);
  }
  for (const auto& l : labels)
  {
    expected.insert(l.id);
  }
  EXPECT_EQ(markers, expected);
  std::ifstream elements(folder.Path() + "/vessel.1.ele");
  long long tetrahedra = 0;
  elements >> tetrahedra;
  EXPECT_GT(tetrahedra, 1000);
}

TEST_P(CfdClient, GmshMeshesTheMultiSolidStl)
{
  BENDER_REQUIRE_PROGRAM("gmsh");
  const auto surface = Surface(GetParam());
  bender::test::TemporaryFolder folder("cfd-gmsh");
  // The case's STL: one ASCII solid per patch, metres.
  bender::CfdCaseOptions caseOptions;
  caseOptions.caseDirectory = folder.Path() + "/case";
  const bender::CfdCaseResult written = bender::WriteOpenFoamCase(surface, caseOptions);
  std::ofstream geo(folder.Path() + "/mesh.geo");
  geo << "Merge \"case/constant/triSurface/vessel.stl\";\n"
         "Surface Loop(1) = Surface{:};\nVolume(1) = {1};\n";
  geo.close();
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  const std::string output =
    RunIn(folder.Path(), "gmsh -3 -nt 1 mesh.geo -format msh22 -o mesh.msh", status);
  std::printf("[ timing ] %s gmsh -3 %.1f s\n", GetParam().name, Seconds(start));
  ASSERT_EQ(status, 0) << output;
  EXPECT_EQ(output.find("Error"), std::string::npos) << output;
  // MSH 2.2: "$Elements" N, then "id type ntags physical elementary nodes...".
  std::ifstream msh(folder.Path() + "/mesh.msh");
  std::string line;
  while (std::getline(msh, line) && line != "$Elements")
  {
  }
  long long count = 0;
  msh >> count;
  ASSERT_GT(count, 0) << output;
  std::map<int, long long> trianglesPerSurface;
  long long tetrahedra = 0;
  for (long long i = 0; i < count; ++i)
  {
    long long id = 0;
    int type = 0, tags = 0;
    msh >> id >> type >> tags;
    std::vector<long long> tagValues(static_cast<std::size_t>(tags));
    for (auto& t : tagValues)
    {
      msh >> t;
    }
    std::getline(msh, line);
    if (type == 2 && tags >= 2)
    {
      ++trianglesPerSurface[static_cast<int>(tagValues[1])];
    }
    else if (type == 4)
    {
      ++tetrahedra;
    }
  }
  EXPECT_GT(tetrahedra, 1000);
  // One discrete surface per solid, with the patch's triangles (surfaces numbered in order).
  ASSERT_EQ(trianglesPerSurface.size(), written.patches.size());
  std::size_t k = 0;
  for (const auto& [tag, n] : trianglesPerSurface)
  {
    EXPECT_EQ(n, written.patches[k].triangles) << written.patches[k].name;
    ++k;
  }
}

INSTANTIATE_TEST_SUITE_P(Vessels,
  CfdClient,
  ::testing::Values(ClientCase{ "aneurysm", false, 1, false, 4.0 },
    ClientCase{ "aneurysm_bent", true, 2, false, 4.0 },
    ClientCase{ "demo", false, 1, true, 4.0 },
    ClientCase{ "demo_bent", true, 1, true, 4.0 }),
  [](const ::testing::TestParamInfo<ClientCase>& info) { return std::string(info.param.name); });

} // namespace
