// The case's boundary conditions and mesh settings without OpenFOAM (CfdBoundaryConditions.h,
// CfdMeshing.h): the developed inlet profile, the inlet by flow rate, the outlets' conditions
// (split, Murray's law, resistances), implausible scales, prism layers and the mesh report.

#include "CfdBoundaryConditions.h"
#include "BenderErrors.h"
#include "CfdCase.h"
#include "CfdDictionaries.h"
#include "CfdMeshing.h"
#include "CfdTestUtilities.h"
#include "CliCommands.h"
#include "MeshIO.h"
#include "PatchLabels.h"

#include <vtkCell.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace fs = std::filesystem;
using bender::test::ReadText;

namespace
{

constexpr double kPi = 3.14159265358979323846;

/// The capped aneurysm, read once for the suite.
vtkPolyData* Aneurysm()
{
  static vtkSmartPointer<vtkPolyData> surface = bender::test::CappedAneurysm(false);
  return surface;
}

/// WriteOpenFoamCase's InputError message, or "no error".
std::string Refusal(vtkPolyData* surface, const bender::CfdCaseOptions& options)
{
  try
  {
    bender::WriteOpenFoamCase(surface, options);
  }
  catch (const bender::InputError& e)
  {
    return e.what();
  }
  return "no error";
}

/// A list of vectors "N ( (x y z) ... )" after an optional // comment line.
std::vector<std::array<double, 3>> ReadVectors(const std::string& path)
{
  std::istringstream in(ReadText(path));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("//", 0), 0u) << path;
  std::size_t n = 0;
  in >> n;
  std::vector<std::array<double, 3>> v(n);
  char c = 0;
  in >> c;
  for (auto& x : v)
  {
    in >> c >> x[0] >> x[1] >> x[2] >> c;
  }
  return v;
}

/// The surface scaled about the origin.
vtkSmartPointer<vtkPolyData> Scaled(vtkPolyData* surface, double factor)
{
  vtkNew<vtkTransform> scale;
  scale->Scale(factor, factor, factor);
  vtkNew<vtkTransformPolyDataFilter> filter;
  filter->SetInputData(surface);
  filter->SetTransform(scale);
  filter->Update();
  vtkSmartPointer<vtkPolyData> out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(filter->GetOutput());
  return out;
}

TEST(CfdInletProfile, PoiseuilleOnACircleCarriesTheFlowWithTwiceTheMeanAtItsCentre)
{
  const auto tube = bender::test::CappedTube(20.0, 2.0, 41, 32);
  const auto labels = bender::ReadPatchLabels(tube);
  const auto ids = bender::CellPatchIds(tube);
  int inlet = 0;
  for (const auto& l : labels)
  {
    inlet = l.type == bender::PatchType::Inlet ? l.id : inlet;
  }
  ASSERT_GT(inlet, 0);
  // The tube's ends face -x and +x; which one is the inlet, its outward normal says.
  double xInlet = 0.0;
  int count = 0;
  for (vtkIdType c = 0; c < tube->GetNumberOfCells(); ++c)
  {
    if (ids[static_cast<std::size_t>(c)] == inlet)
    {
      double x[3];
      tube->GetPoint(tube->GetCell(c)->GetPointId(0), x);
      xInlet += x[0];
      ++count;
    }
  }
  xInlet /= count;
  const std::array<double, 3> normal{ xInlet < 10.0 ? -1.0 : 1.0, 0.0, 0.0 };
  const double q = 2e-6;
  const bender::CfdInletProfileData profile =
    bender::PoiseuilleInletProfile(tube, ids, { inlet, normal, q, 0.0 }, "tube");
  ASSERT_EQ(profile.points.size(), profile.velocities.size());
  EXPECT_NEAR(profile.flowRate, q, 1e-12 * q);
  EXPECT_DOUBLE_EQ(profile.faceCorrection, 1.0);
  // For faces of 0.5 mm the samples are lowered by 1 + h^2 / (3 R^2).
  const bender::CfdInletProfileData faces =
    bender::PoiseuilleInletProfile(tube, ids, { inlet, normal, q, 0.5e-3 }, "tube");
  EXPECT_NEAR(faces.flowRate * (1.0 + 0.25 / 12.0), q, 0.01 * q);
  EXPECT_NEAR(faces.flowRate / faces.faceCorrection, q, 1e-12 * q);
  EXPECT_NEAR(profile.area, kPi * 4e-6, 0.02 * kPi * 4e-6); // the cap of a 32-gon
  // Poiseuille in a circle: the peak is twice the mean, at the centre, 0 on the rim, and the
  // flow goes in.
  EXPECT_NEAR(profile.peakToMean, 2.0, 0.06);
  const double mean = q / profile.area;
  double peak = 0.0;
  for (std::size_t i = 0; i < profile.points.size(); ++i)
  {
    const auto& x = profile.points[i];
    const auto& u = profile.velocities[i];
    const double r = std::hypot(x[1], x[2]) / 2e-3; // in radii
    const double along = u[0] * -normal[0];
    EXPECT_GE(along, 0.0);
    EXPECT_NEAR(std::hypot(u[1], u[2]), 0.0, 1e-12);
    if (r > 0.999)
    {
      EXPECT_NEAR(along, 0.0, 0.05 * mean) << "on the rim";
    }
    // 1 - r^2 within the polygon's error (the rim's sagitta is 0.5 % of the radius).
    EXPECT_NEAR(along, 2.0 * mean * (1.0 - r * r), 0.1 * mean) << "r " << r;
    peak = std::max(peak, along);
  }
  EXPECT_NEAR(peak / mean, profile.peakToMean, 1e-9);
}

TEST(CfdInletProfile, TheWrittenProfileIntegratesToTheFlowRate)
{
  bender::test::TemporaryFolder folder("cfd-profile");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  const bender::CfdCaseResult r = bender::WriteOpenFoamCase(Aneurysm(), options);
  EXPECT_EQ(r.inletProfile, bender::CfdInletProfile::Poiseuille);
  EXPECT_DOUBLE_EQ(r.inletFlowRate, 1e-5) << "the inlet by flow rate by default";
  const std::string u = ReadText(options.caseDirectory + "/0/U");
  EXPECT_NE(u.find("type            timeVaryingMappedFixedValue;"), std::string::npos) << u;
  const auto points = ReadVectors(options.caseDirectory + "/constant/boundaryData/inlet/points");
  const auto velocities = ReadVectors(options.caseDirectory + "/constant/boundaryData/inlet/0/U");
  ASSERT_EQ(points.size(), velocities.size());
  ASSERT_GT(points.size(), 100u);
  // The written samples, integrated over the surface's inlet cap: each cap triangle's thirds
  // (two corners and the centroid, found among the samples by position), u.n linear on each.
  const bender::CfdPatch* inlet = nullptr;
  for (const auto& p : r.patches)
  {
    inlet = p.name == "inlet" ? &p : inlet;
  }
  ASSERT_NE(inlet, nullptr);
  std::vector<double> inward(points.size());
  double peak = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    inward[i] = -(velocities[i][0] * inlet->normal[0] + velocities[i][1] * inlet->normal[1] +
      velocities[i][2] * inlet->normal[2]);
    EXPECT_GE(inward[i], -1e-12) << "into the vessel";
    peak = std::max(peak, inward[i]);
  }
  // The sample at x (within 1 nm), if any.
  auto sample = [&](const std::array<double, 3>& x, double& u)
  {
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      if (std::abs(points[i][0] - x[0]) + std::abs(points[i][1] - x[1]) +
          std::abs(points[i][2] - x[2]) <
        1e-9)
      {
        u = inward[i];
        return true;
      }
    }
    return false;
  };
  const auto ids = bender::CellPatchIds(Aneurysm());
  int inletId = 0;
  for (const auto& l : bender::ReadPatchLabels(Aneurysm()))
  {
    inletId = l.name == "inlet" ? l.id : inletId;
  }
  double flow = 0.0;
  std::size_t found = 0, triangles = 0;
  for (vtkIdType c = 0; c < Aneurysm()->GetNumberOfCells(); ++c)
  {
    if (ids[static_cast<std::size_t>(c)] != inletId)
    {
      continue;
    }
    ++triangles;
    std::array<std::array<double, 3>, 4> x{};
    for (vtkIdType k = 0; k < 3; ++k)
    {
      double mm[3];
      Aneurysm()->GetPoint(Aneurysm()->GetCell(c)->GetPointId(k), mm);
      for (std::size_t d = 0; d < 3; ++d)
      {
        x[static_cast<std::size_t>(k)][d] = 1e-3 * mm[d];
        x[3][d] += 1e-3 * mm[d] / 3.0;
      }
    }
    std::array<double, 4> u{};
    bool all = true;
    for (std::size_t k = 0; k < 4; ++k)
    {
      all = sample(x[k], u[k]) && all;
    }
    found += all ? 1 : 0;
    for (std::size_t k = 0; k < 3; ++k)
    {
      const auto& a = x[k];
      const auto& b = x[(k + 1) % 3];
      const std::array<double, 3> ab{ b[0] - a[0], b[1] - a[1], b[2] - a[2] };
      const std::array<double, 3> ag{ x[3][0] - a[0], x[3][1] - a[1], x[3][2] - a[2] };
      const double area = 0.5 *
        std::sqrt(std::pow(ab[1] * ag[2] - ab[2] * ag[1], 2) +
          std::pow(ab[2] * ag[0] - ab[0] * ag[2], 2) + std::pow(ab[0] * ag[1] - ab[1] * ag[0], 2));
      flow += area * (u[k] + u[(k + 1) % 3] + u[3]) / 3.0;
    }
  }
  EXPECT_EQ(found, triangles) << "every corner and centroid of the cap is a sample";
  // The samples carry the flow lowered by the midpoint rule's excess on the wall's cells
  // (1 + h^2 / (3 R^2), a few percent), the same factor as their peak.
  const double correction = flow / r.inletFlowRate;
  EXPECT_LT(correction, 1.0);
  EXPECT_GT(correction, 1.0 / (1.0 + std::pow(r.cellSize / 3e-3, 2) / 3.0));
  const double mean = r.inletFlowRate / inlet->area;
  EXPECT_NEAR(peak / mean / correction, r.inletPeakToMean, 0.005 * r.inletPeakToMean);
  EXPECT_GT(r.inletPeakToMean, 1.8);
  EXPECT_LT(r.inletPeakToMean, 2.2);

  // The same flow for the bent shape, whose inlet area differs: compared cases carry the
  // same flow.
  options.caseDirectory = folder.Path() + "/bent";
  const bender::CfdCaseResult bent =
    bender::WriteOpenFoamCase(bender::test::CappedAneurysm(true), options);
  EXPECT_DOUBLE_EQ(bent.inletFlowRate, r.inletFlowRate);

  // The plug: flowRateInletVelocity, no boundaryData.
  options.caseDirectory = folder.Path() + "/plug";
  options.inletProfile = bender::CfdInletProfile::Plug;
  const bender::CfdCaseResult plug = bender::WriteOpenFoamCase(Aneurysm(), options);
  EXPECT_DOUBLE_EQ(plug.inletPeakToMean, 1.0);
  EXPECT_NE(
    ReadText(options.caseDirectory + "/0/U").find("flowRateInletVelocity"), std::string::npos);
  EXPECT_FALSE(fs::exists(options.caseDirectory + "/constant/boundaryData"));
}

TEST(CfdInletProfile, TheAverageFollowsTheProfileAndTheAllrunHoldsItOnTheMeshedInlet)
{
  bender::test::TemporaryFolder folder("cfd-inlet-average");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  const bender::CfdCaseResult r = bender::WriteOpenFoamCase(Aneurysm(), options);
  const std::string valuesPath = options.caseDirectory + "/constant/boundaryData/inlet/0/U";
  const std::string values = ReadText(valuesPath);
  const std::size_t marker = values.find(bender::kCfdInletAverageMarker);
  ASSERT_NE(marker, std::string::npos) << values;
  EXPECT_NE(values.rfind("\n)\n", marker), std::string::npos) << "after the profile's list";
  // As written: the flow over the cap's area, into the domain (against the cap's normal), and
  // not yet applied (0/U: setAverage false until the mesh's inlet is known).
  std::istringstream average(values.substr(values.find('\n', marker)));
  char open = 0;
  std::array<double, 3> u{};
  average >> open >> u[0] >> u[1] >> u[2];
  ASSERT_EQ(open, '(');
  const bender::CfdPatch* inlet = nullptr;
  for (const auto& p : r.patches)
  {
    inlet = p.name == "inlet" ? &p : inlet;
  }
  ASSERT_NE(inlet, nullptr);
  const double speed = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  EXPECT_NEAR(speed, r.inletFlowRate / inlet->area, 1e-6 * speed);
  EXPECT_NEAR((u[0] * inlet->normal[0] + u[1] * inlet->normal[1] + u[2] * inlet->normal[2]) / speed,
    -1.0,
    1e-6);
  // 0/U maps the profile when read (no value to stand in for it) and leaves the average off
  // until the Allrun's mesh step has measured the meshed inlet (system/inletFlow) and put the
  // mean that carries the flow there (CfdLayersTest runs it: the flow to 1e-4).
  const std::string field = ReadText(options.caseDirectory + "/0/U");
  const std::size_t bc = field.find("timeVaryingMappedFixedValue");
  ASSERT_NE(bc, std::string::npos);
  const std::string inletEntry = field.substr(bc, field.find('}', bc) - bc);
  EXPECT_NE(inletEntry.find("setAverage      false;"), std::string::npos) << inletEntry;
  EXPECT_EQ(inletEntry.find("        value "), std::string::npos) << inletEntry;
  const std::string flowDict = ReadText(options.caseDirectory + "/system/inletFlow");
  EXPECT_NE(flowDict.find("areaNormalIntegrate"), std::string::npos) << flowDict;
  EXPECT_NE(flowDict.find("name            inlet;"), std::string::npos) << flowDict;
  const std::string allrun = ReadText(options.caseDirectory + "/Allrun");
  EXPECT_NE(allrun.find("postProcess -dict system/inletFlow -time 0"), std::string::npos);
  EXPECT_NE(allrun.find("-v q=1e-05"), std::string::npos) << "the flow to carry, m^3/s";
  EXPECT_NE(allrun.find("constant/boundaryData/inlet/0/U"), std::string::npos);
  EXPECT_LT(allrun.find("checkMesh checkMesh"), allrun.find("postProcess -dict"))
    << "measured on the checked mesh";

  // A plug inlet: OpenFOAM sets the flow itself, nothing to measure.
  options.caseDirectory = folder.Path() + "/plug";
  options.inletProfile = bender::CfdInletProfile::Plug;
  bender::WriteOpenFoamCase(Aneurysm(), options);
  EXPECT_FALSE(fs::exists(options.caseDirectory + "/system/inletFlow"));
  EXPECT_EQ(
    ReadText(options.caseDirectory + "/Allrun").find("postProcess -dict"), std::string::npos);
}

TEST(CfdOutlets, MurraysSplitFollowsTheCubeOfTheRadiiAndSumsToTheInletsFlow)
{
  bender::test::TemporaryFolder folder("cfd-outlets");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  options.outlets = bender::CfdOutletCondition::Murray;
  const bender::CfdCaseResult r = bender::WriteOpenFoamCase(Aneurysm(), options);
  ASSERT_EQ(r.outlets.size(), 2u);
  double percent = 0.0, flow = 0.0;
  int references = 0;
  std::map<std::string, double> diameter;
  for (const auto& p : r.patches)
  {
    diameter[p.name] = p.diameter;
  }
  for (const auto& o : r.outlets)
  {
    percent += o.percent;
    flow += o.flowRate;
    references += o.pressureReference ? 1 : 0;
  }
  EXPECT_NEAR(percent, 100.0, 1e-9);
  EXPECT_NEAR(flow, r.inletFlowRate, 1e-12 * r.inletFlowRate);
  EXPECT_EQ(references, 1) << "one outlet holds p = 0";
  const auto& a = r.outlets[0];
  const auto& b = r.outlets[1];
  EXPECT_NEAR(a.flowRate / b.flowRate, std::pow(diameter[a.name] / diameter[b.name], 3), 1e-9);
  // The larger share holds p = 0; the other its flow.
  const auto& held = a.percent > b.percent ? b : a;
  const auto& reference = a.percent > b.percent ? a : b;
  EXPECT_TRUE(reference.pressureReference);
  const std::string u = ReadText(options.caseDirectory + "/0/U");
  const std::string p = ReadText(options.caseDirectory + "/0/p");
  EXPECT_NE(u.find(held.name + "\n    {\n        // "), std::string::npos) << u;
  EXPECT_NE(u.find("flowRateOutletVelocity;\n        volumetricFlowRate constant " +
              bender::CfdNumber(held.flowRate) + ";"),
    std::string::npos)
    << u;
  EXPECT_NE(
    p.find(reference.name + "\n    {\n        type            fixedValue;"), std::string::npos)
    << p;
  EXPECT_NE(p.find(held.name + "\n    {\n        type            zeroGradient;"), std::string::npos)
    << p;
  const std::string report = bender::FormatCfdBoundaryConditions(r);
  EXPECT_NE(report.find("Murray's law"), std::string::npos) << report;
  // The report states the wall cells across each end, at least the 8 of the default grading.
  EXPECT_NE(report.find("wall cells across each end"), std::string::npos) << report;
  for (const bender::CfdEndCells& e : r.grading.ends)
  {
    EXPECT_GE(e.cellsAcross, 0.99 * 8.0) << e.name; // within 1 %
    EXPECT_NE(
      report.find(" " + e.name + " " + bender::CfdShort(e.cellsAcross, 2)), std::string::npos)
      << report;
  }
}

TEST(CfdOutlets, APrescribedSplitAndResistancesAndTheirRefusals)
{
  bender::test::TemporaryFolder folder("cfd-outlets");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  options.force = true;
  options.outlets = bender::CfdOutletCondition::Split;
  options.outletValues = { { "outlet_1", 70.0 }, { "outlet_2", 30.0 } };
  bender::CfdCaseResult r = bender::WriteOpenFoamCase(Aneurysm(), options);
  ASSERT_EQ(r.outlets.size(), 2u);
  EXPECT_NEAR(r.outlets[0].percent + r.outlets[1].percent, 100.0, 1e-9);
  EXPECT_TRUE(r.outlets[0].name == "outlet_1" && r.outlets[0].pressureReference);
  EXPECT_NEAR(r.outlets[1].flowRate, 0.3 * r.inletFlowRate, 1e-15);
  const nlohmann::json record =
    nlohmann::json::parse(ReadText(options.caseDirectory + "/bender-case.json"));
  EXPECT_EQ(record.at("outletCondition"), "split");
  EXPECT_EQ(record.at("inletProfile"), "poiseuille");
  EXPECT_EQ(record.at("layers"), 3);
  EXPECT_DOUBLE_EQ(record.at("outlets").at(1).at("percentOfInlet").get<double>(), 30.0);

  // Refused, one line naming the option and the outlet.
  auto refused = [&](std::vector<bender::CfdOutletValue> values, const std::string& expected)
  {
    bender::CfdCaseOptions bad = options;
    bad.outletValues = std::move(values);
    const std::string message = Refusal(Aneurysm(), bad);
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };
  refused({ { "outlet_1", 70.0 }, { "outlet_2", 20.0 } }, "--split: the outlets' shares sum to 90");
  refused({ { "outlet_1", 70.0 } }, "--split: give a value for every outlet (outlet_2 has none");
  refused({ { "outlet_1", 70.0 }, { "outlet_9", 30.0 } }, "--split outlet_9: no such outlet");
  refused({ { "inlet", 70.0 }, { "outlet_2", 30.0 } }, "--split inlet: not an outlet");
  refused(
    { { "outlet_1", 130.0 }, { "outlet_2", -30.0 } }, "--split outlet_2=-30: give a value > 0");
  refused({ { "outlet_1", 50.0 }, { "outlet_1", 50.0 } }, "--split outlet_1: given twice");
  bender::CfdCaseOptions murray = options;
  murray.outlets = bender::CfdOutletCondition::Murray;
  EXPECT_NE(Refusal(Aneurysm(), murray).find("not with --outlets murray"), std::string::npos);

  // Resistances: fanPressure with a linear curve of slope -R / rho (kinematic).
  options.outlets = bender::CfdOutletCondition::Resistance;
  options.outletValues = { { "outlet_1", 1e8 }, { "outlet_2", 2e8 } };
  r = bender::WriteOpenFoamCase(Aneurysm(), options);
  const std::string p = ReadText(options.caseDirectory + "/0/p");
  EXPECT_NE(p.find("type            fanPressure;"), std::string::npos) << p;
  for (const auto& o : r.outlets)
  {
    EXPECT_FALSE(o.pressureReference);
    const std::string curve = ReadText(options.caseDirectory + "/constant/resistance/" + o.name);
    std::istringstream in(curve.substr(curve.find("(0 0)") + 5));
    char c = 0;
    double q = 0.0, rise = 0.0;
    in >> c >> q >> rise;
    EXPECT_GT(q, r.inletFlowRate);
    EXPECT_NEAR(-rise / q * options.density, o.resistance, 1e-6 * o.resistance) << curve;
  }
  EXPECT_NE(bender::FormatCfdBoundaryConditions(r).find("resistances p = R Q"), std::string::npos);

  // NAME=VALUE items.
  const auto parsed = bender::ParseCfdOutletValues("--split", { "a=60", "b=40.5" });
  ASSERT_EQ(parsed.size(), 2u);
  EXPECT_EQ(parsed[1].name, "b");
  EXPECT_DOUBLE_EQ(parsed[1].value, 40.5);
  for (const char* item : { "a", "=3", "a=", "a=3x", "a=x" })
  {
    try
    {
      bender::ParseCfdOutletValues("--split", { item });
      ADD_FAILURE() << item;
    }
    catch (const bender::InputError& e)
    {
      EXPECT_EQ(
        std::string(e.what()), "--split " + std::string(item) + ": give NAME=VALUE (outlet_1=60)");
    }
  }
}

TEST(CfdScale, AVesselInTheWrongUnitIsRefusedWithTheLikelyCause)
{
  bender::test::TemporaryFolder folder("cfd-scale");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  options.sourceName = "aneurysm.stl";
  // Written in metres, read as millimetres: an 8 um inlet.
  const std::string small = Refusal(Scaled(Aneurysm(), 1e-3), options);
  EXPECT_NE(small.find("aneurysm.stl: its widest end is "), std::string::npos) << small;
  EXPECT_NE(
    small.find("the vessel looks 1000x too small; was it written in metres?"), std::string::npos)
    << small;
  const std::string large = Refusal(Scaled(Aneurysm(), 1e3), options);
  EXPECT_NE(large.find("the vessel looks 1000x too large; was it written in micrometres?"),
    std::string::npos)
    << large;
  EXPECT_FALSE(fs::exists(options.caseDirectory));
  // A small but real vessel (a 0.5 mm tube) and a large one (the aneurysm x 5) are accepted.
  EXPECT_EQ(Refusal(bender::test::CappedTube(5.0, 0.25, 21, 32), options), "no error");
  options.force = true;
  EXPECT_EQ(Refusal(Scaled(Aneurysm(), 5.0), options), "no error");
}

TEST(CfdMesh, PrismLayersOnTheWallAndTheirReport)
{
  bender::test::TemporaryFolder folder("cfd-layers");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  bender::CfdCaseResult r = bender::WriteOpenFoamCase(Aneurysm(), options);
  EXPECT_EQ(r.layers, 3);
  std::string snappy = ReadText(options.caseDirectory + "/system/snappyHexMeshDict");
  EXPECT_NE(snappy.find("addLayers       true;"), std::string::npos);
  EXPECT_NE(snappy.find("wall { nSurfaceLayers 3; }"), std::string::npos) << snappy;
  EXPECT_EQ(snappy.find("inlet { nSurfaceLayers"), std::string::npos) << "no layers on the ends";
  EXPECT_NE(snappy.find("maxBoundarySkewness 4;"), std::string::npos);
  options.layers = 0;
  options.force = true;
  r = bender::WriteOpenFoamCase(Aneurysm(), options);
  snappy = ReadText(options.caseDirectory + "/system/snappyHexMeshDict");
  EXPECT_NE(snappy.find("addLayers       false;"), std::string::npos);
  EXPECT_EQ(snappy.find("nSurfaceLayers"), std::string::npos);
  options.layers = 11;
  EXPECT_EQ(Refusal(Aneurysm(), options), "--layers 11: give 0 to 10");

  // The report read from the meshers' logs (in the form OpenFOAM 1912 writes them).
  const std::string dir = options.caseDirectory;
  std::ofstream(dir + "/log.checkMesh")
    << "Mesh stats\n    points:           48089\n    cells:            39812\n"
       " ***Max skewness = 4.59, 2 highly skew faces detected\n\nFailed 1 mesh checks.\n";
  std::ofstream(dir + "/log.snappyHexMesh")
    << "patch faces    layers avg thickness[m]\n"
       "Extruding 6579 out of 6633 faces (99.185889%). Removed extrusion at 22 faces.\n"
       "Extruding 6504 out of 6633 faces (98.055179%). Removed extrusion at 0 faces.\n"
       "patch faces    layers   overall thickness\n                       [m]       [%]\n"
       "----- -----    ------   ---       ---\nwall 6633     2.85     0.000731  73.5    \n\n"
       "Layer mesh : cells:39812\n";
  nlohmann::json record = nlohmann::json::parse(ReadText(dir + "/bender-case.json"));
  record["layers"] = 3;
  std::ofstream(dir + "/bender-case.json") << record.dump(2);
  const bender::CfdMeshReport report = bender::ReadCfdMeshReport(dir);
  EXPECT_EQ(report.cells, 39812);
  EXPECT_FALSE(report.meshOk);
  EXPECT_NE(report.failedChecks.find("Max skewness = 4.59"), std::string::npos);
  ASSERT_EQ(report.layers.size(), 1u);
  EXPECT_EQ(report.layers[0].name, "wall");
  EXPECT_EQ(report.layers[0].faces, 6633);
  EXPECT_NEAR(report.layers[0].coveragePercent, 100.0 * 2.85 / 3.0, 1e-9);
  EXPECT_DOUBLE_EQ(report.layers[0].thicknessPercent, 73.5);
  EXPECT_EQ(report.facesExtruded, 6504);
  EXPECT_EQ(report.facesToExtrude, 6633);
  const std::string text = bender::FormatCfdMeshReport(report);
  EXPECT_NE(text.find("checkMesh failed:"), std::string::npos) << text;
  EXPECT_NE(text.find("layers failed on 129 of 6633 faces"), std::string::npos) << text;
  EXPECT_DOUBLE_EQ(bender::CfdMeshReportJson(report).at("wallFacesWithLayersPercent").get<double>(),
    100.0 * 6504 / 6633);
  fs::remove(dir + "/log.checkMesh");
  EXPECT_THROW(bender::ReadCfdMeshReport(dir), bender::InputError);
}

TEST(CfdCaseCommand, TheNewOptionsAndTheirRefusals)
{
  bender::test::TemporaryFolder folder("cfd-cli");
  const std::string surface = folder.Path() + "/aneurysm.vtp";
  bender::WriteMesh(Aneurysm(), surface);
  auto run = [&](std::vector<std::string> args)
  {
    args.insert(args.begin(), { "cfd-case", surface, "-o", folder.Path() + "/case", "--force" });
    return bender::RunBenderCli(args);
  };
  EXPECT_EQ(run({ "--outlets", "murray", "--inlet-profile", "plug", "--layers", "2" }), 0);
  nlohmann::json record = nlohmann::json::parse(ReadText(folder.Path() + "/case/bender-case.json"));
  EXPECT_EQ(record.at("outletCondition"), "murray");
  EXPECT_EQ(record.at("inletProfile"), "plug");
  EXPECT_EQ(record.at("layers"), 2);
  EXPECT_DOUBLE_EQ(record.at("flowRate").get<double>(), 1e-5);
  EXPECT_EQ(run({ "--split", "outlet_1=60,outlet_2=40" }), 0);
  record = nlohmann::json::parse(ReadText(folder.Path() + "/case/bender-case.json"));
  EXPECT_EQ(record.at("outletCondition"), "split");
  EXPECT_EQ(run({ "--resistance", "outlet_1=1e8,outlet_2=1e8", "--velocity", "0.2" }), 0);
  record = nlohmann::json::parse(ReadText(folder.Path() + "/case/bender-case.json"));
  EXPECT_EQ(record.at("outletCondition"), "resistance");
  EXPECT_DOUBLE_EQ(record.at("velocity").get<double>(), 0.2);
  // Refused: exit 1 (bad values) or 2 (usage).
  EXPECT_EQ(run({ "--split", "outlet_1=60" }), 1);
  EXPECT_EQ(run({ "--split", "outlet_1=sixty,outlet_2=40" }), 1);
  EXPECT_EQ(run({ "--outlets", "murray", "--split", "outlet_1=60,outlet_2=40" }), 1);
  EXPECT_EQ(run({ "--outlets", "windkessel" }), 2);
  EXPECT_EQ(run({ "--split", "outlet_1=60,outlet_2=40", "--resistance", "outlet_1=1" }), 2);
  EXPECT_EQ(run({ "--layers", "11" }), 2);
  EXPECT_EQ(run({ "--inlet-profile", "parabolic" }), 2);
  EXPECT_EQ(run({ "--flow-rate", "1e-5", "--velocity", "0.2" }), 2);
}

} // namespace
