// The flow results of a real run (issue 23, "Results back on the vessel"), label `cfd`: a small
// generated tube meshed and solved by OpenFOAM, its results read with vtkOpenFOAMReader and
// mapped onto the surface; and the faults: a diverged field, results that do not match the
// surface, a solver killed mid-run, OpenFOAM missing, each leaving the previous results, and a
// clean re-run. One case is meshed once and shared by the tests of the suite.

#include "BenderErrors.h"
#include "CfdCase.h"
#include "CfdFlowResults.h"
#include "CfdTestUtilities.h"
#include "FileSizeLimit.h"
#include "MeshIO.h"
#include "PatchLabels.h"

#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using bender::test::ReadText;

namespace
{

// The tube: 4 mm across, 40 mm long, 0.05 m/s (Re 57: developed within ~12 mm of the inlet).
constexpr double kRadiusMm = 2.0;
constexpr double kLengthMm = 40.0;
constexpr double kVelocity = 0.05;

class CfdFlowRun : public ::testing::Test
{
protected:
  static void SetUpTestSuite()
  {
    if (bender::FindOpenFoamProblem().empty())
    {
      Folder = new bender::test::TemporaryFolder("cfd-flow-run");
      bender::CfdCaseOptions options;
      options.caseDirectory = Folder->Path() + "/case";
      options.velocity = kVelocity;
      options.iterations = 400;
      Written =
        bender::WriteOpenFoamCase(bender::test::CappedTube(kLengthMm, kRadiusMm, 81, 32), options);
      const auto start = std::chrono::steady_clock::now();
      try
      {
        First = bender::RunOpenFoamCase(options.caseDirectory);
      }
      catch (const std::exception& e)
      {
        RunError = e.what();
      }
      RunSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf("[ timing ] tube case meshed, solved and mapped in %.1f s\n", RunSeconds);
    }
  }
  static void TearDownTestSuite()
  {
    delete Folder;
    Folder = nullptr;
  }
  void SetUp() override
  {
    BENDER_REQUIRE_PROGRAM("simpleFoam");
    BENDER_REQUIRE_PROGRAM("snappyHexMesh");
    ASSERT_TRUE(RunError.empty()) << RunError << "\n" << ReadText(Case() + "/log.Allrun");
    ASSERT_TRUE(First.flow.has_value());
  }
  static std::string Case() { return Written.caseDirectory; }

  static bender::test::TemporaryFolder* Folder;
  static bender::CfdCaseResult Written;
  static bender::CfdRunResult First;
  static std::string RunError;
  static double RunSeconds; ///< wall time of the first run
};

bender::test::TemporaryFolder* CfdFlowRun::Folder = nullptr;
bender::CfdCaseResult CfdFlowRun::Written;
bender::CfdRunResult CfdFlowRun::First;
std::string CfdFlowRun::RunError;
double CfdFlowRun::RunSeconds = 0.0;

/// The entries of the case folder whose name holds "results" (results and its temporaries).
int ResultsEntries(const std::string& caseDirectory)
{
  int entries = 0;
  for (const auto& e : fs::directory_iterator(caseDirectory))
  {
    entries += e.path().filename().string().find("results") != std::string::npos ? 1 : 0;
  }
  return entries;
}

/// Everything in CASE/results, and the entries beside it (no temporary folder left).
std::string ResultsState(const std::string& caseDirectory)
{
  std::string state;
  for (const auto& e : fs::directory_iterator(caseDirectory))
  {
    const std::string name = e.path().filename().string();
    if (name.find("results") != std::string::npos)
    {
      state += name + "\n";
    }
  }
  for (const char* file : { "surface.vtp", "volume.vtu", "flow.json" })
  {
    state += file + std::string(": ") + ReadText(caseDirectory + "/results/" + file) + "\n";
  }
  return state;
}

TEST_F(CfdFlowRun, PressureAndWallShearStressOnTheSurface)
{
  const bender::CfdFlowResults& flow = *First.flow;
  std::printf("%s", bender::FormatCfdRun(First).c_str());
  EXPECT_TRUE(flow.run.converged) << flow.run.status;
  EXPECT_EQ(flow.run.status.rfind("converged in ", 0), 0u) << flow.run.status;
  EXPECT_GT(flow.meshCells, 1000);

  const auto surface = bender::ReadMesh(Case() + "/results/surface.vtp");
  // The case's surface: LPS mm, its labels kept.
  const auto labels = bender::ReadPatchLabels(surface);
  ASSERT_EQ(labels.size(), 3u);
  double bounds[6];
  surface->GetBounds(bounds);
  EXPECT_NEAR(bounds[0], 0.0, 1e-6);
  EXPECT_NEAR(bounds[1], kLengthMm, 1e-6);
  vtkDataArray* pressure = surface->GetPointData()->GetArray(bender::kPressureArrayName);
  vtkDataArray* wss = surface->GetPointData()->GetArray(bender::kWallShearStressArrayName);
  vtkDataArray* magnitude =
    surface->GetPointData()->GetArray(bender::kWallShearStressMagnitudeArrayName);
  ASSERT_TRUE(pressure && wss && magnitude);
  ASSERT_EQ(wss->GetNumberOfComponents(), 3);

  // The wall pressure falls from the inlet to the outlet, in 5 mm slices along the tube.
  const int slices = 8;
  std::vector<double> sum(slices, 0.0), count(slices, 0.0);
  double developed = 0.0, developedCount = 0.0;
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    double x[3];
    surface->GetPoint(i, x);
    const double r = std::hypot(x[1], x[2]);
    if (r < 0.99 * kRadiusMm)
    {
      continue; // a cap's inner point
    }
    const int slice = std::min(slices - 1, static_cast<int>(x[0] / (kLengthMm / slices)));
    sum[slice] += pressure->GetTuple1(i);
    count[slice] += 1.0;
    EXPECT_NEAR(magnitude->GetTuple1(i),
      std::sqrt(wss->GetTuple3(i)[0] * wss->GetTuple3(i)[0] +
        wss->GetTuple3(i)[1] * wss->GetTuple3(i)[1] + wss->GetTuple3(i)[2] * wss->GetTuple3(i)[2]),
      1e-9);
    if (x[0] > 20.0 && x[0] < 32.0)
    {
      developed += magnitude->GetTuple1(i);
      developedCount += 1.0;
    }
  }
  for (int s = 1; s < slices; ++s)
  {
    EXPECT_LT(sum[s] / count[s], sum[s - 1] / count[s - 1]) << "slice " << s;
  }
  // Relative to the outlet (the one outlet, at p = 0): the outlet end near 0, the inlet end
  // at the pressure drop.
  EXPECT_LT(std::abs(sum[slices - 1] / count[slices - 1]), 0.25 * sum[0] / count[0]);
  ASSERT_EQ(flow.ends.size(), 2u);
  EXPECT_EQ(flow.ends[0].name, "inlet");
  EXPECT_NEAR(flow.ends[1].meanPressurePa, 0.0, 1e-9);
  EXPECT_EQ(flow.ends[0].pressureDropPa, 0.0);
  EXPECT_GT(flow.ends[1].pressureDropPa, 0.0);
  EXPECT_NEAR(flow.ends[1].pressureDropPa, flow.ends[0].meanPressurePa, 1e-9);
  EXPECT_NEAR(flow.ends[1].splitPercent, 100.0, 1.0);

  // The developed part: Poiseuille's 8 mu U / D with the mean velocity of the flow through
  // the snapped tube (a coarse mesh without layers: within 25 %).
  const double mu = 3.5e-6 * 1060.0;
  const double meanVelocity =
    flow.inletFlowRateMlPerMin / 6e7 / (M_PI * std::pow(kRadiusMm * 1e-3, 2));
  const double poiseuille = 8.0 * mu * meanVelocity / (2.0 * kRadiusMm * 1e-3);
  ASSERT_GT(developedCount, 0.0);
  std::printf("developed WSS %.4g Pa, Poiseuille 8 mu U / D %.4g Pa\n",
    developed / developedCount,
    poiseuille);
  EXPECT_NEAR(developed / developedCount, poiseuille, 0.25 * poiseuille);
  EXPECT_GT(flow.wallShearStress.maxPa, flow.wallShearStress.meanPa);
  EXPECT_GE(flow.wallShearStress.percentile99Pa, flow.wallShearStress.meanPa);
  EXPECT_NEAR(flow.wallShearStress.wallAreaMm2, 2.0 * M_PI * kRadiusMm * kLengthMm, 0.02 * 503);

  // volume.vtu: U in m/s at points in mm, along +x inside the tube.
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((Case() + "/results/volume.vtu").c_str());
  reader->Update();
  vtkUnstructuredGrid* volume = reader->GetOutput();
  ASSERT_GT(volume->GetNumberOfCells(), 0);
  volume->GetBounds(bounds);
  EXPECT_NEAR(bounds[1] - bounds[0], kLengthMm, 1.0);
  vtkDataArray* u = volume->GetPointData()->GetArray(bender::kVelocityArrayName);
  ASSERT_TRUE(u);
  EXPECT_GT(u->GetRange(0)[1], 1.5 * kVelocity);

  // flow.json reads back to the same results.
  const bender::CfdFlowResults back = bender::ReadCfdFlowResults(Case());
  EXPECT_EQ(bender::CfdFlowResultsToJson(back), bender::CfdFlowResultsToJson(flow));
}

// The run's stages timed (CfdStageTimes.h): every Allrun step in order, the stages adding up to
// the steps and the mapping, within the wall time the suite measured around the run.
TEST_F(CfdFlowRun, TheRunIsTimedStageByStage)
{
  const bender::CfdStageTimes& t = First.stages;
  std::vector<std::string> programs;
  double steps = 0.0;
  for (const auto& [program, seconds] : t.steps)
  {
    programs.push_back(program);
    steps += seconds;
  }
  EXPECT_EQ(programs,
    std::vector<std::string>({ "blockMesh",
      "surfaceFeatureExtract",
      "snappyHexMesh",
      "checkMesh",
      "postProcess",
      "simpleFoam" }));
  EXPECT_GT(t.mesh, 0.0);
  EXPECT_GT(t.layers, 0.0); // the case has 3 prism layers
  EXPECT_GT(t.solve, 0.0);
  EXPECT_GT(t.map, 0.0);
  EXPECT_NEAR(t.Total(), steps + t.map, 1e-9);
  EXPECT_LE(t.Total(), RunSeconds);
}

/// A fault: `action` must throw E with a one-line message containing `what`, and leave
/// CASE/results as it was.
template<typename E, typename Action>
void ExpectFaultKeepsResults(const std::string& caseDirectory,
  const std::string& what,
  Action action)
{
  const std::string before = ResultsState(caseDirectory);
  try
  {
    action();
    ADD_FAILURE() << "no error (expected " << what << ")";
  }
  catch (const E& e)
  {
    const std::string message = e.what();
    EXPECT_NE(message.find(what), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_EQ(ResultsState(caseDirectory), before) << "the previous results changed";
}

/// The latest time folder of the case.
std::string LatestTime(const std::string& caseDirectory)
{
  double latest = -1.0;
  std::string name;
  for (const auto& e : fs::directory_iterator(caseDirectory))
  {
    char* end = nullptr;
    const std::string n = e.path().filename().string();
    const double t = std::strtod(n.c_str(), &end);
    if (end && *end == '\0' && t > latest)
    {
      latest = t;
      name = n;
    }
  }
  return caseDirectory + "/" + name;
}

TEST_F(CfdFlowRun, ADivergedFieldIsNamedAndKeepsThePreviousResults)
{
  const std::string p = LatestTime(Case()) + "/p";
  const std::string original = ReadText(p);
  // The first value of the internal field becomes nan, as a diverged run writes it.
  const std::string diverged = std::regex_replace(original,
    std::regex(R"((internalField\s+nonuniform List<scalar>\s*\d+\s*\(\s*)[^\s)]+)"),
    "$1nan",
    std::regex_constants::format_first_only);
  ASSERT_NE(diverged, original);
  std::ofstream(p) << diverged;
  ExpectFaultKeepsResults<bender::Error>(
    Case(), "the solution diverged: p is not finite", [&] { bender::MapCfdResults(Case()); });
  std::ofstream(p) << original;
}

TEST_F(CfdFlowRun, ResultsThatDoNotMatchTheSurfaceAreRefused)
{
  const std::string boundary = Case() + "/constant/polyMesh/boundary";
  const std::string original = ReadText(boundary);
  std::ofstream(boundary) << std::regex_replace(original, std::regex("outlet_1"), "outlet_9");
  ExpectFaultKeepsResults<bender::InputError>(Case(),
    "the results do not match the surface: its patch outlet_1 is not a patch of the mesh",
    [&] { bender::MapCfdResults(Case()); });
  std::ofstream(boundary) << original;
}

// A full disk while the results are written (simulated by the file size limit, half the
// smallest of surface.vtp and volume.vtu): one line naming the results folder and the file, the
// previous results kept,
// no temporary folder left beside them; with room again the results are written whole.
TEST_F(CfdFlowRun, AFullDiskKeepsThePreviousResults)
{
  const std::uintmax_t smallest = std::min(
    fs::file_size(Case() + "/results/surface.vtp"), fs::file_size(Case() + "/results/volume.vtu"));
  ExpectFaultKeepsResults<bender::Error>(Case(),
    Case() + "/results: surface.vtp: write error (",
    [&]
    {
      bender::test::FileSizeLimit limit(smallest / 2);
      bender::MapCfdResults(Case());
    });
  EXPECT_EQ(ResultsEntries(Case()), 1);
  const bender::CfdFlowResults again = bender::MapCfdResults(Case());
  EXPECT_EQ(bender::CfdFlowResultsToJson(again), bender::CfdFlowResultsToJson(*First.flow));
  EXPECT_EQ(ResultsEntries(Case()), 1);
}

TEST_F(CfdFlowRun, MissingOpenFoamKeepsThePreviousResults)
{
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  bender::test::TemporaryFolder empty("cfd-no-openfoam");
  setenv("PATH", empty.Path().c_str(), 1);
  ExpectFaultKeepsResults<bender::EnvironmentError>(Case(),
    "OpenFOAM is not installed: blockMesh is not on PATH",
    [&] { bender::RunOpenFoamCase(Case()); });
  setenv("PATH", path.c_str(), 1);
}

TEST_F(CfdFlowRun, ASolverKilledMidRunKeepsThePreviousResultsAndARerunIsClean)
{
  // simpleFoam killed (SIGKILL) once it has iterated, through a wrapper first on PATH (its
  // output is log.simpleFoam). A solver that finished between two looks still exits as
  // killed, so the test does not depend on the machine's speed.
  bender::test::TemporaryFolder bin("cfd-killed-solver");
  const std::string real = bender::FindExecutable("simpleFoam");
  std::ofstream(bin.Path() + "/simpleFoam")
    << "#!/bin/sh\n\"" << real << "\" \"$@\" &\npid=$!\n"
    << "while kill -0 $pid 2>/dev/null && ! grep -q '^Time = 3$' log.simpleFoam; do\n"
    << "    sleep 0.05\ndone\nkill -9 $pid 2>/dev/null\nwait $pid\nexit 137\n";
  fs::permissions(bin.Path() + "/simpleFoam", fs::perms::owner_all);
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  setenv("PATH", (bin.Path() + ":" + path).c_str(), 1);
  bender::CfdRunOptions solve;
  solve.steps = bender::CfdRunOptions::Steps::Solve;
  ExpectFaultKeepsResults<bender::Error>(Case(),
    "simpleFoam failed, see log.simpleFoam",
    [&] { bender::RunOpenFoamCase(Case(), solve); });
  setenv("PATH", path.c_str(), 1);

  // Run again: the same results, written whole, nothing left beside them.
  const bender::CfdRunResult again = bender::RunOpenFoamCase(Case(), solve);
  ASSERT_TRUE(again.flow.has_value());
  EXPECT_EQ(again.flow->run.iterations, First.flow->run.iterations);
  EXPECT_NEAR(again.flow->wallShearStress.meanPa, First.flow->wallShearStress.meanPa, 1e-6);
  EXPECT_EQ(ResultsEntries(Case()), 1);
}

TEST_F(CfdFlowRun, CommandLineCarriesTheFlowResults)
{
  bender::test::TemporaryFolder folder("cfd-flow-cli");
  const std::string surface = folder.Path() + "/tube.vtp";
  bender::WriteMesh(bender::test::CappedTube(kLengthMm, kRadiusMm, 81, 32), surface);
  const std::string cli = std::string(BENDER_CLI_PATH) + " cfd-case " + surface + " -o " +
    folder.Path() + "/case --velocity 0.05 --iterations 400 --run";
  // OpenFOAM missing: one line, exit status 1, no results.
  int status = 0;
  const std::string missing =
    bender::test::RunIn(folder.Path(), "PATH=/nonexistent " + cli + " --json", status);
  EXPECT_EQ(status, 1) << missing;
  EXPECT_NE(missing.find("OpenFOAM is not installed"), std::string::npos) << missing;
  EXPECT_EQ(std::count(missing.begin(), missing.end(), '\n'), 1) << missing;
  EXPECT_FALSE(fs::exists(folder.Path() + "/case/results"));
  // Killed while writing the results (BENDER_FAULT_AT, FaultInjection.h): no results folder,
  // only the temporary one beside it, which the next mapping clears.
  const std::string killed =
    bender::test::RunIn(folder.Path(), "BENDER_FAULT_AT=cfd-results " + cli + " --json", status);
  EXPECT_EQ(status, 128 + 9) << killed; // the shell reports the SIGKILL
  EXPECT_FALSE(fs::exists(folder.Path() + "/case/results"));
  EXPECT_EQ(ResultsEntries(folder.Path() + "/case"), 1) << "the temporary results folder";
  EXPECT_NO_THROW(bender::MapCfdResults(folder.Path() + "/case"));
  EXPECT_EQ(ResultsEntries(folder.Path() + "/case"), 1);
  EXPECT_TRUE(fs::exists(folder.Path() + "/case/results/flow.json"));
  // --json: the whole of flow.json as "flow".
  const std::string json =
    bender::test::RunIn(folder.Path(), cli + " --force --json 2>/dev/null", status);
  ASSERT_EQ(status, 0) << json;
  const nlohmann::json j = nlohmann::json::parse(json);
  const nlohmann::json written =
    nlohmann::json::parse(ReadText(folder.Path() + "/case/results/flow.json"));
  EXPECT_EQ(j.at("flow"), written);
  EXPECT_EQ(j.at("flow").at("format"), "bender-flow-results");
  EXPECT_TRUE(j.at("run").at("converged").get<bool>());
  EXPECT_NEAR(j.at("flow").at("wallShearStress").at("mean_Pa").get<double>(),
    First.flow->wallShearStress.meanPa,
    1e-6);
}

} // namespace
