// WriteOpenFoamCase, ReadCfdResults and bender-cli cfd-case without OpenFOAM: the files of the
// case, its errors, all-or-nothing writing and the reading of the function objects' results.

#include "CfdCase.h"
#include "BenderErrors.h"
#include "BenderMeshCheck.h"
#include "CfdTestUtilities.h"
#include "CfdVerificationTubes.h"
#include "CfdWallEnds.h"
#include "CliCommands.h"
#include "FileSizeLimit.h"
#include "InsidePoint.h"
#include "LabelledSurface.h"
#include "MeshIO.h"
#include "PatchLabels.h"
#include "RunDemo.h"

#include <vtkCell.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSelectEnclosedPoints.h>
#include <vtkSphereSource.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <regex>
#include <sstream>

namespace fs = std::filesystem;
using bender::test::ReadText;

namespace
{

/// bender-cli cfd-case in-process.
int RunCfdCaseCommand(std::vector<std::string> args)
{
  args.insert(args.begin(), "cfd-case");
  return bender::RunBenderCli(args);
}

/// The capped aneurysm, read once for the suite.
vtkPolyData* Aneurysm()
{
  static vtkSmartPointer<vtkPolyData> surface = bender::test::CappedAneurysm(false);
  return surface;
}

std::size_t Count(const std::string& text, const std::string& what)
{
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
  {
    ++n;
  }
  return n;
}

/// Files and folders directly in folder (the temporary siblings of a failed write included).
std::size_t Entries(const std::string& folder)
{
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(folder))
  {
    (void)e;
    ++n;
  }
  return n;
}

TEST(CfdCase, WritesACompleteCaseInMetres)
{
  bender::test::TemporaryFolder folder("cfd-case");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  options.flowRate = 4e-6;
  options.inletProfile = bender::CfdInletProfile::Plug;
  options.processors = 4;
  options.iterations = 321;
  options.viscosity = 4e-6;
  const bender::CfdCaseResult r = bender::WriteOpenFoamCase(Aneurysm(), options);
  const std::string dir = options.caseDirectory;
  for (const char* file : { "constant/triSurface/vessel.stl",
         "system/blockMeshDict",
         "system/surfaceFeatureExtractDict",
         "system/snappyHexMeshDict",
         "system/controlDict",
         "system/fvSchemes",
         "system/fvSolution",
         "system/decomposeParDict",
         "constant/transportProperties",
         "constant/turbulenceProperties",
         "0/U",
         "0/p",
         "Allrun",
         "bender-case.json" })
  {
    EXPECT_TRUE(fs::is_regular_file(dir + "/" + file)) << file;
  }
  EXPECT_NE(fs::status(dir + "/Allrun").permissions() & fs::perms::owner_exec, fs::perms::none);

  // The patches: the wall and three ends, the largest end the inlet; sizes in metres.
  ASSERT_EQ(r.patches.size(), 4u);
  EXPECT_EQ(r.inlet, "inlet");
  EXPECT_EQ(r.patches[0].name, "wall");
  double largestEnd = 0.0;
  for (const auto& p : r.patches)
  {
    if (p.type != bender::PatchType::Wall)
    {
      EXPECT_GT(p.diameter, 3e-3) << p.name;
      EXPECT_LT(p.diameter, 1e-2) << p.name;
      EXPECT_NEAR(std::hypot(std::hypot(p.normal[0], p.normal[1]), p.normal[2]), 1.0, 1e-9);
      largestEnd = std::max(largestEnd, p.diameter);
    }
  }
  // The default base cell: 8 across the largest end (narrower ends refined: CfdGradingTest).
  EXPECT_NEAR(r.cellSize, largestEnd / 8.0, 1e-12);
  EXPECT_DOUBLE_EQ(r.inletFlowRate, 4e-6);

  // The STL: a named ASCII solid per patch, coordinates in metres (the aneurysm is ~55 mm).
  const std::string stl = ReadText(dir + "/constant/triSurface/vessel.stl");
  for (const auto& p : r.patches)
  {
    EXPECT_EQ(Count("\n" + stl, "\nsolid " + p.name + "\n"), 1u) << p.name;
    EXPECT_EQ(Count(stl, "endsolid " + p.name), 1u) << p.name;
  }
  std::smatch m;
  std::string::const_iterator from = stl.cbegin();
  double largest = 0.0;
  std::regex vertex("vertex ([-0-9.e+]+) ([-0-9.e+]+) ([-0-9.e+]+)");
  for (int i = 0; i < 2000 && std::regex_search(from, stl.cend(), m, vertex); ++i)
  {
    for (int k = 1; k <= 3; ++k)
    {
      largest = std::max(largest, std::abs(std::stod(m[static_cast<std::size_t>(k)].str())));
    }
    from = m.suffix().first;
  }
  EXPECT_GT(largest, 0.005);
  EXPECT_LT(largest, 0.1);

  // The inside point is inside the surface (mm), away from the wall.
  vtkNew<vtkSelectEnclosedPoints> enclosed;
  enclosed->Initialize(Aneurysm());
  double inside[3] = { 1e3 * r.insidePoint[0], 1e3 * r.insidePoint[1], 1e3 * r.insidePoint[2] };
  EXPECT_TRUE(enclosed->IsInsideSurface(inside));
  enclosed->Complete();
  // It is Bender's one inside point (the sidecar's), moved off the grid by a few hundredths
  // of a cell.
  const std::optional<bender::LumenPoint> lumen =
    bender::FindInsidePoint(bender::ReadLabelledSurface(Aneurysm()));
  ASSERT_TRUE(lumen.has_value());
  const double shared[3] = { lumen->point.x, lumen->point.y, lumen->point.z };
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_NEAR(inside[k], shared[k], 0.05 * 1e3 * r.cellSize) << k;
  }
  EXPECT_LT(0.05 * 1e3 * r.cellSize, lumen->clearance);
  const std::string snappy = ReadText(dir + "/system/snappyHexMeshDict");
  EXPECT_NE(snappy.find("locationInMesh ("), std::string::npos);
  for (const auto& p : r.patches)
  {
    EXPECT_NE(snappy.find(p.name + " { name " + p.name + "; }"), std::string::npos) << p.name;
    std::string level = "1";
    for (const bender::CfdEndCells& e : r.grading.ends)
    {
      level = e.name == p.name ? std::to_string(e.level) : level;
    }
    EXPECT_NE(snappy.find(p.name + " { level (" + level + " " + level + "); patchInfo { type " +
                (p.type == bender::PatchType::Wall ? "wall" : "patch")),
      std::string::npos)
      << p.name;
  }

  // The background box holds the surface with a margin.
  double bounds[6];
  Aneurysm()->GetBounds(bounds);
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_GE(r.backgroundCells[static_cast<std::size_t>(k)] * r.backgroundCellSize,
      1e-3 * (bounds[2 * k + 1] - bounds[2 * k]) + 2 * r.backgroundCellSize);
  }

  // Boundary conditions, solver settings, function objects per end.
  const std::string u = ReadText(dir + "/0/U");
  EXPECT_EQ(Count(u, "flowRateInletVelocity"), 1u);
  EXPECT_NE(u.find("volumetricFlowRate constant 4e-06;"), std::string::npos) << u;
  EXPECT_EQ(Count(u, "noSlip"), 1u);
  EXPECT_EQ(Count(u, "inletOutlet"), 2u);
  const std::string p = ReadText(dir + "/0/p");
  EXPECT_EQ(Count(p, "fixedValue"), 2u);
  EXPECT_EQ(Count(p, "zeroGradient"), 2u);
  const std::string control = ReadText(dir + "/system/controlDict");
  EXPECT_NE(control.find("endTime         321;"), std::string::npos);
  EXPECT_EQ(Count(control, "type            surfaceFieldValue;"), 6u);
  EXPECT_EQ(Count(control, "type            solverInfo;"), 1u);
  const std::string decompose = ReadText(dir + "/system/decomposeParDict");
  EXPECT_NE(decompose.find("numberOfSubdomains 4;"), std::string::npos);
  EXPECT_NE(decompose.find("method          hierarchical;"), std::string::npos);
  std::smatch split;
  ASSERT_TRUE(
    std::regex_search(decompose, split, std::regex("n +\\(([0-9]+) ([0-9]+) ([0-9]+)\\)")))
    << decompose;
  EXPECT_EQ(std::stoi(split[1]) * std::stoi(split[2]) * std::stoi(split[3]), 4);
  EXPECT_NE(ReadText(dir + "/constant/transportProperties").find("4e-06;"), std::string::npos);
  const std::string allrun = ReadText(dir + "/Allrun");
  EXPECT_NE(allrun.find("processors=4"), std::string::npos);
  EXPECT_NE(allrun.find("mpirun -np \"$processors\" simpleFoam -parallel"), std::string::npos);
  EXPECT_NE(allrun.find("snappyHexMesh -overwrite"), std::string::npos);
  EXPECT_EQ(Entries(folder.Path()), 1u) << "no temporary folder left beside the case";
}

TEST(CfdCase, TheCaseOfALabelledSurfaceIsTheCaseOfThePlainSurface)
{
  bender::test::TemporaryFolder folder("cfd-case-labelled");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/plain";
  const bender::CfdCaseResult plain = bender::WriteOpenFoamCase(Aneurysm(), options);
  options.caseDirectory = folder.Path() + "/labelled";
  const bender::CfdCaseResult labelled =
    bender::WriteOpenFoamCase(bender::ReadLabelledSurface(Aneurysm()), options);
  ASSERT_EQ(plain.written, labelled.written);
  for (const std::string& file : plain.written)
  {
    const std::string a = ReadText(folder.Path() + "/plain/" + file);
    const std::string b = ReadText(folder.Path() + "/labelled/" + file);
    EXPECT_FALSE(a.empty()) << file;
    EXPECT_EQ(a, b) << file;
  }
}

TEST(CfdCase, VelocityInletAndNamedInlet)
{
  bender::test::TemporaryFolder folder("cfd-case");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  options.velocity = 0.3;
  options.inletProfile = bender::CfdInletProfile::Plug;
  options.inlet = "outlet_2";
  // The surface's ends: inlet, outlet_1, outlet_2 (label order, as the case's patches).
  const std::vector<bender::PatchLabel> labels = bender::ReadPatchLabels(Aneurysm());
  std::size_t chosen = labels.size(), former = labels.size();
  for (std::size_t k = 0; k < labels.size(); ++k)
  {
    chosen = labels[k].name == "outlet_2" ? k : chosen;
    former = labels[k].name == "inlet" ? k : former;
  }
  ASSERT_LT(chosen, labels.size());
  ASSERT_LT(former, labels.size());
  const bender::CfdCaseResult r = bender::WriteOpenFoamCase(Aneurysm(), options);
  // The chosen end is the inlet and is called so; the former inlet is an outlet and takes the
  // chosen end's outlet name (names and roles agree, issue 23).
  EXPECT_EQ(r.inlet, "inlet");
  ASSERT_EQ(r.patches.size(), labels.size());
  EXPECT_EQ(r.patches[chosen].name, "inlet");
  EXPECT_EQ(r.patches[chosen].type, bender::PatchType::Inlet);
  EXPECT_EQ(r.patches[former].name, "outlet_2");
  EXPECT_EQ(r.patches[former].type, bender::PatchType::Outlet);
  int inlets = 0;
  for (const auto& p : r.patches)
  {
    if (p.type == bender::PatchType::Inlet)
    {
      ++inlets;
      EXPECT_NEAR(r.inletFlowRate, 0.3 * p.area, 1e-15);
    }
  }
  EXPECT_EQ(inlets, 1);
  // The same names and roles in bender-case.json, the STL's solids and the labelled VTP.
  const std::string json = ReadText(options.caseDirectory + "/bender-case.json");
  EXPECT_NE(json.find("\"inlet\": \"inlet\""), std::string::npos) << json;
  const std::string stl = ReadText(options.caseDirectory + "/constant/triSurface/vessel.stl");
  EXPECT_EQ(Count(stl, "endsolid inlet\n"), 1u);
  EXPECT_EQ(Count(stl, "endsolid outlet_2\n"), 1u);
  const auto vtp = bender::ReadMesh(options.caseDirectory + "/constant/triSurface/vessel.vtp");
  const std::vector<bender::PatchLabel> written = bender::ReadPatchLabels(vtp);
  ASSERT_EQ(written.size(), r.patches.size());
  for (std::size_t k = 0; k < written.size(); ++k)
  {
    EXPECT_EQ(written[k].id, labels[k].id);
    EXPECT_EQ(written[k].name, r.patches[k].name);
    EXPECT_EQ(written[k].type, r.patches[k].type);
  }
  // The input surface keeps its own labels.
  EXPECT_EQ(bender::ReadPatchLabels(Aneurysm())[former].name, "inlet");
  // The inlet's velocity on the patch called inlet; the former inlet is an outlet at p = 0.
  auto block = [](const std::string& text, const std::string& patch)
  {
    const std::size_t at = text.find("\n    " + patch + "\n    {");
    return at == std::string::npos ? std::string() : text.substr(at, text.find("\n    }", at) - at);
  };
  const std::string u = ReadText(options.caseDirectory + "/0/U");
  EXPECT_NE(block(u, "inlet").find("surfaceNormalFixedValue"), std::string::npos) << u;
  EXPECT_NE(block(u, "inlet").find("uniform -0.3;"), std::string::npos) << u;
  const std::string p = ReadText(options.caseDirectory + "/0/p");
  EXPECT_NE(block(p, "outlet_2").find("fixedValue"), std::string::npos) << p;
  EXPECT_EQ(block(p, "inlet").find("fixedValue"), std::string::npos) << p;
}

TEST(CfdCase, RefusesSurfacesThatCannotMakeAFlowCase)
{
  bender::test::TemporaryFolder folder("cfd-case");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  options.sourceName = "x.vtp";
  auto message = [&](vtkPolyData* surface, const bender::CfdCaseOptions& o)
  {
    try
    {
      bender::WriteOpenFoamCase(surface, o);
    }
    catch (const bender::InputError& e)
    {
      return std::string(e.what());
    }
    return std::string("no error");
  };

  // Open: the aneurysm as gmsh wrote it.
  vtkSmartPointer<vtkPolyData> open =
    bender::ReadMesh(std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl");
  EXPECT_NE(message(open, options).find("x.vtp: the surface is not closed ("), std::string::npos)
    << message(open, options);
  EXPECT_NE(message(open, options).find(" boundary edges in 3 open loops"), std::string::npos);

  // Closed, but one labelled end only.
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(24);
  sphere->SetRadius(5.0);
  sphere->Update();
  vtkNew<vtkPolyData> ball;
  ball->DeepCopy(sphere->GetOutput());
  std::vector<int> ids(static_cast<std::size_t>(ball->GetNumberOfCells()), 1);
  ids[0] = 2;
  bender::WritePatchLabels(ball,
    ids,
    { { 1, "wall", bender::PatchType::Wall }, { 2, "inlet", bender::PatchType::Inlet } });
  EXPECT_NE(message(ball, options)
              .find("a flow case needs an inlet and at least one outlet, the "
                    "surface has 1 labelled end(s)"),
    std::string::npos)
    << message(ball, options);
  // No label at all: the wall alone.
  EXPECT_NE(message(sphere->GetOutput(), options).find("has 0 labelled end(s)"), std::string::npos);

  // Two ends, none labelled inlet.
  ids[1] = 3;
  bender::WritePatchLabels(ball,
    ids,
    { { 1, "wall", bender::PatchType::Wall },
      { 2, "a", bender::PatchType::Outlet },
      { 3, "b", bender::PatchType::Outlet } });
  EXPECT_NE(
    message(ball, options).find("no end is labelled inlet: name it with --inlet (ends: a, b)"),
    std::string::npos)
    << message(ball, options);
  auto named = options;
  named.inlet = "c";
  EXPECT_NE(
    message(ball, named).find("--inlet c: x.vtp has no such end (ends: a, b)"), std::string::npos);
  named.inlet = "wall";
  EXPECT_NE(message(ball, named).find("--inlet wall: is the wall"), std::string::npos);
  named.inlet = "b";
  EXPECT_EQ(message(ball, named), "no error");

  // Options out of range.
  auto bad = options;
  bad.force = true;
  bad.cellSize = -1.0;
  EXPECT_NE(message(ball, bad).find("--cell-size"), std::string::npos);
  bad.cellSize = 1e-7;
  bad.inlet = "b";
  EXPECT_NE(message(ball, bad).find("give a larger cell size"), std::string::npos);
  bad = options;
  bad.viscosity = std::nan("");
  EXPECT_NE(message(ball, bad).find("--viscosity"), std::string::npos);
  bad = options;
  bad.processors = 0;
  EXPECT_NE(message(ball, bad).find("--processors"), std::string::npos);
  EXPECT_EQ(message(nullptr, options), "x.vtp: no triangles");
}

TEST(CfdCase, NeverLeavesAHalfWrittenCaseAndReplacesOnlyWithForce)
{
  bender::test::TemporaryFolder folder("cfd-case");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  options.inletProfile = bender::CfdInletProfile::Plug;
  // An empty folder is used.
  fs::create_directory(options.caseDirectory);
  bender::WriteOpenFoamCase(Aneurysm(), options);
  EXPECT_TRUE(fs::exists(options.caseDirectory + "/Allrun"));
  // A non-empty one is refused, and kept as it was.
  std::ofstream(options.caseDirectory + "/mine.txt") << "keep";
  options.velocity = 0.5;
  EXPECT_THROW(bender::WriteOpenFoamCase(Aneurysm(), options), bender::InputError);
  EXPECT_EQ(ReadText(options.caseDirectory + "/mine.txt"), "keep");
  EXPECT_EQ(ReadText(options.caseDirectory + "/0/U").find("-0.5"), std::string::npos);
  // With force it is replaced whole.
  options.force = true;
  bender::WriteOpenFoamCase(Aneurysm(), options);
  EXPECT_FALSE(fs::exists(options.caseDirectory + "/mine.txt"));
  EXPECT_NE(ReadText(options.caseDirectory + "/0/U").find("-0.5"), std::string::npos);
  EXPECT_EQ(Entries(folder.Path()), 1u);
  // A failure after the checks (the STL export refuses a non-finite point) leaves nothing.
  vtkNew<vtkPolyData> broken;
  broken->DeepCopy(Aneurysm());
  broken->GetPoints()->SetPoint(0, std::nan(""), 0.0, 0.0);
  bender::CfdCaseOptions fresh;
  fresh.caseDirectory = folder.Path() + "/other";
  EXPECT_THROW(bender::WriteOpenFoamCase(broken, fresh), bender::Error);
  EXPECT_FALSE(fs::exists(fresh.caseDirectory));
  EXPECT_EQ(Entries(folder.Path()), 1u);
  // A file is not a folder.
  std::ofstream(folder.Path() + "/file") << "x";
  fresh.caseDirectory = folder.Path() + "/file";
  fresh.force = true;
  EXPECT_THROW(bender::WriteOpenFoamCase(Aneurysm(), fresh), bender::InputError);
  EXPECT_EQ(ReadText(folder.Path() + "/file"), "x");
}

/// Every file and folder under `folder` with its content (folders: empty).
std::map<std::string, std::string> CaseFiles(const std::string& folder)
{
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(folder))
  {
    files[e.path().string()] = e.is_regular_file() ? ReadText(e.path().string()) : "";
  }
  return files;
}

// Issue 23: a full disk while the case is written (simulated by the file size limit, which the
// STL of the surface, about 2 MB, exceeds): one line naming the case and the file that failed,
// the previous case kept as it was, nothing left beside it.
TEST(CfdCase, AFullDiskKeepsThePreviousCase)
{
  bender::test::TemporaryFolder folder("cfd-case");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  bender::WriteOpenFoamCase(Aneurysm(), options);
  const std::map<std::string, std::string> before = CaseFiles(options.caseDirectory);
  options.force = true;
  options.flowRate = 2e-5;
  std::string message = "no error";
  {
    bender::test::FileSizeLimit limit(256 * 1024);
    try
    {
      bender::WriteOpenFoamCase(Aneurysm(), options);
    }
    catch (const bender::Error& e)
    {
      message = e.what();
    }
  }
  EXPECT_EQ(message.rfind(options.caseDirectory + ": ", 0), 0u) << message;
  EXPECT_NE(message.find("write failed"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_TRUE(CaseFiles(options.caseDirectory) == before) << "the previous case changed";
  EXPECT_EQ(Entries(folder.Path()), 1u);

  // The command under the same limit (inherited, as SIGXFSZ ignored): exit 1, one line.
  const std::string surface = folder.Path() + "/capped.vtp";
  bender::WriteMesh(Aneurysm(), surface);
  int status = 0;
  std::string output;
  {
    bender::test::FileSizeLimit limit(256 * 1024);
    output = bender::test::RunIn(folder.Path(),
      std::string(BENDER_CLI_PATH) + " cfd-case capped.vtp -o case --force --flow-rate 2e-5",
      status);
  }
  EXPECT_EQ(status, 1) << output;
  EXPECT_NE(output.find("case: vessel.stl: write failed"), std::string::npos) << output;
  EXPECT_EQ(Count(output, "\n"), 1u) << output;
  EXPECT_TRUE(CaseFiles(options.caseDirectory) == before)
    << "the command changed the previous case";
  EXPECT_EQ(Entries(folder.Path()), 2u); // the case and capped.vtp
}

// Issue 23: an end whose cap is labelled wall would be closed in the case, the flow going
// elsewhere; cfd-case refuses it before anything is written, with or without --run, naming where
// the end is. The capped aneurysm with its outlet_2 labelled wall.
TEST(CfdCase, AnEndLabelledAsWallIsRefusedBeforeAnythingIsWritten)
{
  // No flat part of a real wall is taken for an end, nor a coarse tube's flat facets.
  EXPECT_TRUE(bender::FindWallEnds(bender::ReadLabelledSurface(Aneurysm()), 0.0).empty());
  EXPECT_TRUE(bender::FindWallEnds(
    bender::ReadLabelledSurface(bender::test::CappedTube(40.0, 2.0, 81, 12)), 0.0)
                .empty());
  // An octagonal tube as long as it is wide: each facet is one flat quad of 3.8 x 10 mm, round
  // enough (4 pi area / perimeter^2 = 0.63), but its rim turns by 45 degrees along its long
  // sides. Its outlet cap, labelled wall, is found.
  vtkSmartPointer<vtkPolyData> octagonal =
    bender::SweepClosedTube(bender::StraightCentreline(0.0, 10.0, 1), 5.0, 8);
  EXPECT_TRUE(bender::FindWallEnds(bender::ReadLabelledSurface(octagonal), 0.0).empty());
  std::vector<int> octagonalIds = bender::CellPatchIds(octagonal);
  std::vector<bender::PatchLabel> octagonalLabels = bender::ReadPatchLabels(octagonal);
  for (int& id : octagonalIds)
  {
    id = id == octagonalLabels.back().id ? bender::kWallEntityId : id;
  }
  octagonalLabels.pop_back();
  bender::WritePatchLabels(octagonal, octagonalIds, octagonalLabels);
  const std::vector<bender::CfdWallEnd> octagonalEnds =
    bender::FindWallEnds(bender::ReadLabelledSurface(octagonal), 0.0);
  ASSERT_EQ(octagonalEnds.size(), 1u);
  EXPECT_NEAR(octagonalEnds[0].centre[0], 10.0, 1e-6);

  vtkNew<vtkPolyData> closedEnd;
  closedEnd->DeepCopy(Aneurysm());
  std::vector<int> ids = bender::CellPatchIds(closedEnd);
  std::vector<bender::PatchLabel> labels = bender::ReadPatchLabels(closedEnd);
  const auto outlet = std::find_if(
    labels.begin(), labels.end(), [](const bender::PatchLabel& p) { return p.name == "outlet_2"; });
  ASSERT_NE(outlet, labels.end());
  // The cap's centre (the mean of its triangles' centroids, nearly the area-weighted one).
  std::array<double, 3> centre{};
  int capTriangles = 0;
  for (std::size_t c = 0; c < ids.size(); ++c)
  {
    if (ids[c] != outlet->id)
    {
      continue;
    }
    vtkCell* cell = closedEnd->GetCell(static_cast<vtkIdType>(c));
    for (int k = 0; k < 3; ++k)
    {
      double x[3];
      closedEnd->GetPoint(cell->GetPointId(k), x);
      for (int i = 0; i < 3; ++i)
      {
        centre[i] += x[i] / 3.0;
      }
    }
    ++capTriangles;
    ids[c] = bender::kWallEntityId;
  }
  ASSERT_GT(capTriangles, 0);
  for (double& x : centre)
  {
    x /= capTriangles;
  }
  labels.erase(outlet);
  bender::WritePatchLabels(closedEnd, ids, labels);

  const std::vector<bender::CfdWallEnd> found =
    bender::FindWallEnds(bender::ReadLabelledSurface(closedEnd), 0.0);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_LT(std::hypot(found[0].centre[0] - centre[0],
              found[0].centre[1] - centre[1],
              found[0].centre[2] - centre[2]),
    0.1 * found[0].diameter);
  EXPECT_EQ(found[0].triangles, capTriangles);

  bender::test::TemporaryFolder folder("cfd-case");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  options.sourceName = "closed.vtp";
  try
  {
    bender::WriteOpenFoamCase(closedEnd, options);
    ADD_FAILURE() << "a case with an end labelled wall was written";
  }
  catch (const bender::InputError& e)
  {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("closed.vtp: the end at (", 0), 0u) << what;
    EXPECT_NE(
      what.find(" mm wide) is labelled wall: the case would close that vessel"), std::string::npos)
      << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  EXPECT_EQ(Entries(folder.Path()), 0u);

  // The command: exit 1, one line, no case.
  const std::string surface = folder.Path() + "/closed.vtp";
  bender::WriteMesh(closedEnd, surface);
  int status = 0;
  const std::string output = bender::test::RunIn(
    folder.Path(), std::string(BENDER_CLI_PATH) + " cfd-case closed.vtp -o case", status);
  EXPECT_EQ(status, 1) << output;
  EXPECT_NE(output.find("is labelled wall"), std::string::npos) << output;
  EXPECT_EQ(Count(output, "\n"), 1u) << output;
  EXPECT_FALSE(fs::exists(folder.Path() + "/case"));
}

void WriteDat(const std::string& dir,
  const std::string& object,
  const std::string& file,
  const std::string& text)
{
  fs::create_directories(dir + "/postProcessing/" + object + "/0");
  std::ofstream(dir + "/postProcessing/" + object + "/0/" + file) << text;
}

TEST(CfdCase, ReadsTheFlowSplitPressureDropAndResiduals)
{
  bender::test::TemporaryFolder folder("cfd-case");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  bender::WriteOpenFoamCase(Aneurysm(), options);
  const std::string dir = options.caseDirectory;
  EXPECT_THROW(bender::ReadCfdResults(dir), bender::InputError); // not run yet
  auto flow = [](double v)
  {
    std::ostringstream s;
    s << std::setprecision(17) << "# Region type : patch\n# Time          \tsum(phi)\n1\t0\n2\t"
      << v << "\n";
    return s.str();
  };
  WriteDat(dir, "flow_inlet", "surfaceFieldValue.dat", flow(-1e-5));
  WriteDat(dir, "flow_outlet_1", "surfaceFieldValue.dat", flow(6e-6));
  WriteDat(dir, "flow_outlet_2", "surfaceFieldValue.dat", flow(3.99e-6));
  WriteDat(dir, "pressure_inlet", "surfaceFieldValue.dat", flow(0.1));
  WriteDat(dir, "pressure_outlet_1", "surfaceFieldValue.dat", flow(0.0));
  WriteDat(dir, "pressure_outlet_2", "surfaceFieldValue.dat", flow(0.0));
  WriteDat(dir,
    "solverInfo",
    "solverInfo.dat",
    "# Solver information\n# Time          \tU_solver        \tUx_initial      \tUx_final        "
    "\tUx_iters        \tUy_initial      \tUy_final        \tUy_iters        \tUz_initial      "
    "\tUz_final        \tUz_iters        \tU_converged     \tp_solver        \tp_initial       "
    "\tp_final         \tp_iters         \tp_converged     \n"
    "2\tsmoothSolver\t1e-3\t1e-5\t2\t2e-3\t1e-5\t2\t3e-3\t1e-5\t2\tfalse\tGAMG\t4e-2\t1e-"
    "4\t4\ttrue\n");
  // Stopped before the 1000 of controlDict without meeting the residual control (killed,
  // cut short): not converged, and said so.
  std::ofstream(dir + "/log.simpleFoam") << "Time = 2\n\nEnd\n";
  const bender::CfdRunResult stopped = bender::ReadCfdResults(dir);
  EXPECT_FALSE(stopped.converged);
  const std::string stoppedText = bender::FormatCfdRun(stopped);
  EXPECT_NE(
    stoppedText.find("simpleFoam: stopped at 2 iterations, residuals Ux 0.001"), std::string::npos)
    << stoppedText;
  std::ofstream(dir + "/log.simpleFoam")
    << "Time = 2\n\nSIMPLE solution converged in 2 iterations\n\nEnd\n";
  const bender::CfdRunResult run = bender::ReadCfdResults(dir);
  EXPECT_EQ(run.iterations, 2);
  EXPECT_TRUE(run.converged);
  EXPECT_DOUBLE_EQ(run.inletFlowRate, 1e-5);
  EXPECT_NEAR(run.massImbalance, 1e-3, 1e-12);
  ASSERT_EQ(run.patches.size(), 3u);
  EXPECT_NEAR(run.patches[1].percentOfInlet, 60.0, 1e-9);
  EXPECT_NEAR(run.patches[2].percentOfInlet, 39.9, 1e-9);
  EXPECT_NEAR(run.patches[0].pressure, 106.0, 1e-9); // 1060 kg/m^3 x 0.1 m^2/s^2
  EXPECT_NEAR(run.patches[1].pressureDrop, 106.0, 1e-9);
  ASSERT_EQ(run.residuals.size(), 4u);
  EXPECT_EQ(run.residuals[0].first, "Ux");
  EXPECT_DOUBLE_EQ(run.residuals[0].second, 1e-3);
  EXPECT_EQ(run.residuals[3].first, "p");
  EXPECT_DOUBLE_EQ(run.residuals[3].second, 4e-2);
  const std::string text = bender::FormatCfdRun(run);
  EXPECT_NE(text.find("outlet_1: 60 % of the inlet flow"), std::string::npos) << text;
  EXPECT_NE(text.find("pressure drop from the inlet 106 Pa"), std::string::npos) << text;
  // A broken value is named.
  WriteDat(dir, "flow_outlet_2", "surfaceFieldValue.dat", "# Time sum(phi)\n2\tnan-ish\n");
  try
  {
    bender::ReadCfdResults(dir);
    ADD_FAILURE() << "no error";
  }
  catch (const bender::InputError& e)
  {
    EXPECT_NE(
      std::string(e.what()).find("flow_outlet_2: 'nan-ish' is not a number"), std::string::npos)
      << e.what();
  }
}

TEST(CfdCase, SaysWhenOpenFoamIsMissing)
{
  bender::test::TemporaryFolder folder("cfd-case");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  bender::WriteOpenFoamCase(Aneurysm(), options);
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  setenv("PATH", folder.Path().c_str(), 1);
  const std::string problem = bender::FindOpenFoamProblem();
  EXPECT_THROW(bender::RunOpenFoamCase(options.caseDirectory), bender::EnvironmentError);
  const int status = RunCfdCaseCommand({ "x.vtp", "-o", folder.Path() + "/c2", "--run" });
  setenv("PATH", path.c_str(), 1);
  EXPECT_EQ(problem.rfind("OpenFOAM is not installed: blockMesh is not on PATH", 0), 0u) << problem;
  EXPECT_EQ(status, 1);
  EXPECT_FALSE(fs::exists(folder.Path() + "/c2"));
}

TEST(CfdCase, CommandLine)
{
  bender::test::TemporaryFolder folder("cfd-case");
  const std::string surface = folder.Path() + "/capped.vtp";
  bender::WriteMesh(Aneurysm(), surface);
  EXPECT_EQ(RunCfdCaseCommand({ "--help" }), 0);
  EXPECT_EQ(RunCfdCaseCommand({ surface }), 2); // no -o
  EXPECT_EQ(RunCfdCaseCommand(
              { surface, "-o", folder.Path() + "/c", "--flow-rate", "1e-6", "--velocity", "0.1" }),
    2);
  EXPECT_EQ(RunCfdCaseCommand({ surface, "-o", folder.Path() + "/c", "--velocity", "0" }), 2);
  EXPECT_EQ(RunCfdCaseCommand({ surface, "-o", folder.Path() + "/c", "--inlet", "nope" }), 1);
  EXPECT_FALSE(fs::exists(folder.Path() + "/c"));
  EXPECT_EQ(RunCfdCaseCommand({ surface,
              "-o",
              folder.Path() + "/c",
              "--flow-rate",
              "2e-6",
              "--processors",
              "2",
              "--cell-size",
              "0.001",
              "--json" }),
    0);
  const std::string json = ReadText(folder.Path() + "/c/bender-case.json");
  EXPECT_NE(json.find("\"flowRate\": 2e-06"), std::string::npos) << json;
  EXPECT_NE(json.find("\"cellSize\": 0.001"), std::string::npos) << json;
  EXPECT_NE(json.find("\"processors\": 2"), std::string::npos) << json;
  // The folder now exists and is not empty.
  EXPECT_EQ(RunCfdCaseCommand({ surface, "-o", folder.Path() + "/c" }), 1);
  EXPECT_EQ(RunCfdCaseCommand({ surface, "-o", folder.Path() + "/c", "--force" }), 0);
  // The real executable registers the command.
  int status = 0;
  const std::string help =
    bender::test::RunIn(folder.Path(), std::string(BENDER_CLI_PATH) + " --help", status);
  EXPECT_NE(help.find("cfd-case"), std::string::npos) << help;
}

} // namespace

namespace
{

TEST(CfdCase, TheDemoJobEndsWithACfdReadyBentVesselAndItsCase)
{
  bender::test::TemporaryFolder folder("cfd-demo");
  bender::RunDemoOptions options;
  options.outputDirectory = folder.Path() + "/demo";
  options.segment = false; // the open aneurysm: its ends are re-cut perpendicular
  options.screenshot = false;
  options.vesselPath = std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl";
  options.planPath = std::string(BENDER_SOURCE_DIR) + "/data/demo/demo.bender.json";
  const bender::RunDemoResult result = bender::RunDemo(options);
  for (const auto& w : result.warnings)
  {
    EXPECT_EQ(w.find("CFD"), std::string::npos) << w;
  }
  ASSERT_EQ(result.cfdCase, options.outputDirectory + "/demo-openfoam");
  for (const char* file : { "demo-cfd.stl",
         "demo-cfd.patches.json",
         "demo-cfd.vtp",
         "demo-openfoam/Allrun",
         "demo-openfoam/constant/triSurface/vessel.stl" })
  {
    EXPECT_TRUE(fs::exists(options.outputDirectory + "/" + file)) << file;
  }
  // The CFD surface: labelled wall, inlet and two outlets, bent like demo-bent (the plan moves
  // it), in metres in the STL.
  const auto cfd = bender::ReadMesh(options.outputDirectory + "/demo-cfd.vtp");
  const auto labels = bender::ReadPatchLabels(cfd);
  ASSERT_EQ(labels.size(), 4u);
  EXPECT_EQ(labels[1].name, "inlet");
  EXPECT_EQ(labels[1].type, bender::PatchType::Inlet);
  // Closed, manifold, outwards and nothing crossing (the check of the export).
  bender::MeshCheckOptions check;
  check.requireClosed = true;
  const bender::MeshCheckReport report = bender::CheckMesh(cfd, nullptr, check);
  EXPECT_TRUE(report.Clean()) << bender::FormatReportText(report, "demo-cfd.vtp");
  const std::string stl = ReadText(options.outputDirectory + "/demo-cfd.stl");
  EXPECT_NE(stl.find("unit m"), std::string::npos);
  EXPECT_NE(stl.find("\nsolid outlet_2\n"), std::string::npos);
  // A second run replaces the case.
  EXPECT_NO_THROW(bender::RunDemo(options));
  EXPECT_TRUE(fs::exists(options.outputDirectory + "/demo-openfoam/Allrun"));
}

} // namespace
