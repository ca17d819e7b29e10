// bender-cli compare and the flow report (issue 23) without OpenFOAM: two cases of the capped
// aneurysm (original and bent by the demo plan) written by WriteOpenFoamCase, with results
// made here (flow.json, and surface.vtp with a pressure and a WSS field), compared in-process.
// The table, the JSON, the PNGs and the PDF (every page rendered by pdftoppm), the bend
// measures, and the one-line errors with nothing written. Renders: label rendering.

#include "CfdTestUtilities.h"
#include "InProcessCli.h"

#include "CfdFlowResults.h"
#include "MeshIO.h"

#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

namespace fs = std::filesystem;

namespace
{
const std::string DemoPlan = std::string(BENDER_SOURCE_DIR) + "/data/demo/demo.bender.json";

// Results for `surface` (mm): Pressure falling by `drop` Pa from the inlet's side over the
// vessel's extent, WSS `wss` Pa with a ripple; flow.json's ends from the case's patches.
void WriteResults(const std::string& caseDir, vtkPolyData* input, double drop, double wss)
{
  vtkSmartPointer<vtkPolyData> surface = vtkSmartPointer<vtkPolyData>::New();
  surface->DeepCopy(input);
  double bounds[6];
  surface->GetBounds(bounds);
  vtkNew<vtkDoubleArray> pressure, stress;
  pressure->SetName(bender::kPressureArrayName);
  stress->SetName(bender::kWallShearStressMagnitudeArrayName);
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    double p[3];
    surface->GetPoint(i, p);
    const double t = (p[2] - bounds[4]) / (bounds[5] - bounds[4]);
    pressure->InsertNextValue(drop * (1.0 - t));
    stress->InsertNextValue(wss * (1.0 + 0.8 * std::sin(p[0] * 0.3) * t));
  }
  surface->GetPointData()->AddArray(pressure);
  surface->GetPointData()->AddArray(stress);
  fs::create_directories(fs::path(caseDir) / bender::kCfdResultsFolder);
  bender::WriteMesh(
    surface, (fs::path(caseDir) / bender::kCfdResultsFolder / bender::kCfdSurfaceResults).string());

  const nlohmann::json record =
    nlohmann::json::parse(bender::test::ReadText(caseDir + "/bender-case.json"));
  bender::CfdFlowResults r;
  r.run.iterations = 300;
  r.run.iterationLimit = 1000;
  r.run.converged = true;
  r.run.status = "converged in 300 iterations";
  r.run.residuals = { { "Ux", 8e-6 }, { "p", 9e-5 } };
  r.inletFlowRateMlPerMin = 600.0;
  int outlet = 0;
  for (const auto& patch : record.at("patches"))
  {
    const std::string type = patch.at("type");
    if (type == "wall")
    {
      continue;
    }
    bender::CfdEndFlow end;
    end.name = patch.at("name");
    end.role = type == "inlet" ? bender::PatchType::Inlet : bender::PatchType::Outlet;
    end.splitPercent = end.role == bender::PatchType::Inlet ? 100.0 : (outlet++ == 0 ? 58.0 : 42.0);
    end.flowRateMlPerMin = 6.0 * end.splitPercent;
    end.pressureDropPa = end.role == bender::PatchType::Inlet ? 0.0 : drop * (0.9 + 0.1 * outlet);
    r.ends.push_back(end);
  }
  r.wallShearStress = bender::ComputeWallShearStats(surface);
  r.meshCells = 50000;
  r.settings.cellSizeMm = 0.3;
  r.settings.reynolds = 400;
  std::ofstream(fs::path(caseDir) / bender::kCfdResultsFolder / bender::kCfdFlowJson)
    << bender::CfdFlowResultsToJson(r);
}

// Two cases with results: A the aneurysm, B bent by the demo plan with more pressure drop and
// WSS. Made once per process (writing them takes a few seconds).
struct Cases
{
  bender::test::TemporaryFolder folder{ "compare" };
  std::string a = folder.Path() + "/original";
  std::string b = folder.Path() + "/bent";
  Cases()
  {
    for (const bool bent : { false, true })
    {
      bender::CfdCaseOptions options;
      options.caseDirectory = bent ? b : a;
      const vtkSmartPointer<vtkPolyData> surface = bender::test::CappedAneurysm(bent);
      bender::WriteOpenFoamCase(surface, options);
      WriteResults(options.caseDirectory, surface, bent ? 60.0 : 45.0, bent ? 3.0 : 2.2);
    }
  }
};

const Cases& TheCases()
{
  static const Cases cases;
  return cases;
}

bendertest::CliRun Compare(std::vector<std::string> args)
{
  args.insert(args.begin(), "compare");
  return bendertest::RunInProcess(args);
}

int CountLines(const std::string& text)
{
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

// The page count of a PDF (pdfinfo), -1 when it cannot be read.
int PdfPages(const std::string& pdf)
{
  int status = 0;
  const std::string info = bender::test::RunIn(".", "pdfinfo '" + pdf + "'", status);
  const size_t at = info.find("Pages:");
  return status == 0 && at != std::string::npos ? std::stoi(info.substr(at + 6)) : -1;
}
} // namespace

TEST(CfdCompare, TheReportHasTheTableThePicturesAndEveryPageRenders)
{
  ASSERT_FALSE(bender::FindExecutable("pdftoppm").empty())
    << "pdftoppm is not installed (scripts/setup installs poppler-utils)";
  const Cases& cases = TheCases();
  bender::test::TemporaryFolder out("compare-out");
  const std::string pdf = out.Path() + "/report.pdf";
  const std::string pngs = out.Path() + "/pictures";
  const bendertest::CliRun r =
    Compare({ cases.a, cases.b, "-o", pdf, "--png", pngs, "--plan", DemoPlan });
  ASSERT_EQ(r.status, 0) << r.err << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
  // The table: both outlets, highlighted pressure drops (45 -> 60 Pa: +33 %).
  for (const char* text : { "Pressure drop to outlet_1 (Pa)",
         "Flow split to outlet_2 (%)",
         "WSS 99th percentile (Pa)",
         "Wall area with WSS < 0.4 Pa (mm^2)",
         "Mesh cells",
         "plan: demo.bender.json",
         "report: " })
  {
    EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
  }
  EXPECT_NE(r.out.find("* Pressure drop to outlet_1"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("* Flow split to outlet_1"), std::string::npos) << r.out;

  // Every page of the PDF renders, and none is blank.
  const int pages = PdfPages(pdf);
  ASSERT_GE(pages, 3) << pdf;
  int status = 0;
  const std::string log =
    bender::test::RunIn(out.Path(), "pdftoppm -r 30 -png report.pdf page", status);
  ASSERT_EQ(status, 0) << log;
  int rendered = 0;
  for (const auto& entry : fs::directory_iterator(out.Path()))
  {
    if (entry.path().filename().string().rfind("page", 0) == 0)
    {
      ++rendered;
      EXPECT_GT(fs::file_size(entry.path()), 1000u) << entry.path();
    }
  }
  EXPECT_EQ(rendered, pages);

  // One PNG per quantity and view, both shapes drawn in colour on each.
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(pngs))
  {
    names.insert(entry.path().filename().string());
    vtkNew<vtkPNGReader> reader;
    reader->SetFileName(entry.path().string().c_str());
    reader->Update();
    vtkImageData* image = reader->GetOutput();
    int dims[3];
    image->GetDimensions(dims);
    ASSERT_GT(dims[0], 200);
    // Coloured (not grey) pixels in the left and in the right half.
    int coloured[2] = { 0, 0 };
    for (int y = 0; y < dims[1]; y += 4)
    {
      for (int x = 0; x < dims[0] * 86 / 100; x += 4)
      {
        const auto* px = static_cast<unsigned char*>(image->GetScalarPointer(x, y, 0));
        const int spread = std::max({ px[0], px[1], px[2] }) - std::min({ px[0], px[1], px[2] });
        coloured[x < dims[0] * 43 / 100 ? 0 : 1] += spread > 60;
      }
    }
    EXPECT_GT(coloured[0], 100) << entry.path();
    EXPECT_GT(coloured[1], 100) << entry.path();
  }
  EXPECT_EQ(names,
    (std::set<std::string>{
      "pressure-iso.png", "pressure-front.png", "wss-iso.png", "wss-front.png" }));
}

TEST(CfdCompare, TheJsonHasTheRowsTheBendsAndThePlan)
{
  const Cases& cases = TheCases();
  bender::test::TemporaryFolder out("compare-json");
  const std::string pdf = out.Path() + "/report.pdf";
  const bendertest::CliRun r =
    Compare({ cases.a, cases.b, "-o", pdf, "--json", "--plan", DemoPlan });
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("format"), "bender-flow-comparison");
  EXPECT_GT(j.at("highlighted").get<int>(), 0);
  EXPECT_EQ(j.at("report").at("pdf"), pdf);
  EXPECT_TRUE(fs::exists(pdf));
  EXPECT_TRUE(j.at("report").at("pngs").empty());
  // The demo plan turns the ribbon's end by about 40 degrees.
  ASSERT_EQ(j.at("plan").at("warps").size(), 1u);
  EXPECT_NEAR(j.at("plan").at("warps")[0].at("endTurn_deg").get<double>(), 40.0, 1.0);
  EXPECT_NE(j.at("plan").at("name").get<std::string>().find("40 degrees"), std::string::npos);
  // Every branch measured in both shapes; the bent branch turned, the others hardly.
  ASSERT_FALSE(j.at("bends").empty()) << j.at("unavailable").dump();
  double largestChange = 0.0;
  for (const auto& bend : j.at("bends"))
  {
    ASSERT_FALSE(bend.at("bendAngleA_deg").is_null()) << bend.dump();
    ASSERT_FALSE(bend.at("bendAngleB_deg").is_null()) << bend.dump();
    EXPECT_GT(bend.at("minRadiusA_mm").get<double>(), 0.0);
    largestChange = std::max(largestChange,
      std::abs(bend.at("bendAngleB_deg").get<double>() - bend.at("bendAngleA_deg").get<double>()));
  }
  EXPECT_GT(largestChange, 10.0);
  // The same rows as the table: the difference is B - A.
  for (const auto& row : j.at("rows"))
  {
    if (!row.at("a").is_null() && !row.at("b").is_null())
    {
      EXPECT_NEAR(row.at("difference").get<double>(),
        row.at("b").get<double>() - row.at("a").get<double>(),
        1e-9);
    }
  }
}

TEST(CfdCompare, BadCasesAndOutputsAreOneLineAndWriteNothing)
{
  const Cases& cases = TheCases();
  bender::test::TemporaryFolder out("compare-bad");
  const std::string pdf = out.Path() + "/report.pdf";
  // A case written but not run.
  const std::string notRun = out.Path() + "/not-run";
  fs::create_directories(notRun);
  fs::copy_file(cases.a + "/bender-case.json", notRun + "/bender-case.json");
  // Run, but the results were not mapped.
  const std::string unmapped = out.Path() + "/unmapped";
  fs::create_directories(unmapped + "/postProcessing");
  fs::copy_file(cases.a + "/bender-case.json", unmapped + "/bender-case.json");
  // Results of another case: an end the case does not have.
  const std::string other = out.Path() + "/other";
  fs::copy(cases.a, other, fs::copy_options::recursive);
  {
    nlohmann::json flow = nlohmann::json::parse(
      bender::test::ReadText(other + "/" + bender::kCfdResultsFolder + "/" + bender::kCfdFlowJson));
    std::string text = flow.dump();
    const std::string from = "\"outlet_2\"";
    text.replace(text.find(from), from.size(), "\"outlet_9\"");
    std::ofstream(other + "/" + bender::kCfdResultsFolder + "/" + bender::kCfdFlowJson) << text;
  }
  const std::string flowJson = cases.a + "/results/flow.json";
  const std::vector<std::pair<std::vector<std::string>, std::string>> bad = {
    { { notRun, cases.b, "-o", pdf }, "has not been run" },
    { { unmapped, cases.b, "-o", pdf }, "results missing" },
    { { other, cases.b, "-o", pdf }, "outlet_9" },
    { { out.Path() + "/nowhere", cases.b, "-o", pdf }, "no such case folder" },
    { { cases.a, cases.a, "-o", pdf }, "the same case" },
    { { cases.a, cases.b, "-o", flowJson }, "refusing to overwrite an input" },
    { { cases.a, cases.b, "-o", out.Path() + "/report.txt" }, "PDF" },
    { { cases.a, cases.b, "-o", pdf, "--plan", out.Path() + "/missing.bender.json" },
      "missing.bender.json" },
  };
  for (const auto& [args, message] : bad)
  {
    const bendertest::CliRun r = Compare(args);
    EXPECT_EQ(r.status, 1) << args[0] << " " << args[3] << ": " << r.err;
    EXPECT_EQ(CountLines(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("bender-cli compare: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << message << ": " << r.err;
    EXPECT_FALSE(fs::exists(pdf)) << r.err;
  }
  // The input the refused output named is intact.
  EXPECT_NO_THROW(nlohmann::json::parse(bender::test::ReadText(flowJson)));
  // Nothing but the folders made above.
  for (const auto& entry : fs::directory_iterator(out.Path()))
  {
    EXPECT_TRUE(entry.is_directory()) << entry.path();
  }
}
