#include "CfdVerification.h"

#include "BenderErrors.h"
#include "CfdCase.h"
#include "CfdFlowResults.h"
#include "CfdLabelledRun.h"
#include "CfdReferenceFlows.h"
#include "CfdVerificationTubes.h"
#include "CfdWallSamples.h"
#include "MeshIO.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

namespace fs = std::filesystem;

namespace bender
{
namespace
{

constexpr double Pi = 3.14159265358979323846;
constexpr double Viscosity = 3.5e-6; // m^2/s, the case's default (blood)
constexpr double Density = 1060.0;   // kg/m^3
constexpr double Diameter = 4.0;     // mm, both tubes
constexpr int Sides = 96;            // points per ring of the generated surface

// The straight tube: 40 D long at Re 100 (entrance length about 6 D: developed from 8 D). Shah's
// correlation fits boundary-layer solutions; the full equations add about 38 / Re to the
// entrance loss coefficient (Chen 1973), 0.6 / (L / D) of the pressure drop whatever Re: 1.5 %
// over 40 D, 3 % over 20 D.
constexpr double StraightLength = 40.0 * Diameter;
constexpr double StraightReynolds = 100.0;
constexpr double DevelopedFrom = 8.0 * Diameter, DevelopedTo = 38.0 * Diameter;

// The curved tube: a torus section of bend radius 2.5 D (a / Rc = 0.2), 300 degrees, Re 200:
// Dean 89; developed from 180 degrees, 30 degrees (1.3 D) clear of the outlet.
constexpr double BendRadius = 2.5 * Diameter;
constexpr double BendAngle = 300.0 * Pi / 180.0;
constexpr double CurvedReynolds = 200.0;
constexpr double CurvedFrom = 180.0 * Pi / 180.0, CurvedTo = 270.0 * Pi / 180.0;

std::string Short(double v, int digits = 3)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", digits, v);
  return text;
}

// A new or empty folder for the cases, or a temporary one (removed by the destructor).
class CasesFolder
{
public:
  explicit CasesFolder(const std::string& folder)
  {
    std::error_code ec;
    if (folder.empty())
    {
      std::random_device random;
      this->Path = fs::temp_directory_path(ec) / ("bender-cfd-verify-" + std::to_string(random()));
      this->Temporary = true;
    }
    else
    {
      this->Path = folder;
      if (fs::exists(this->Path, ec) &&
        (!fs::is_directory(this->Path, ec) || !fs::is_empty(this->Path, ec)))
      {
        throw InputError(folder + ": not an empty folder (give a new or empty one)");
      }
    }
    fs::create_directories(this->Path, ec);
    if (ec)
    {
      throw InputError(this->Path.string() + ": cannot create the folder (" + ec.message() + ")");
    }
  }
  ~CasesFolder()
  {
    if (this->Temporary)
    {
      std::error_code ec;
      fs::remove_all(this->Path, ec);
    }
  }
  CasesFolder(const CasesFolder&) = delete;
  CasesFolder& operator=(const CasesFolder&) = delete;
  fs::path Path;
  bool Temporary = false;
};

// Writes the generated surface beside its case, writes the case (flow rate prescribed so that the
// mean velocity is exact whatever the snapped inlet's area), runs it and maps its results.
CfdVerificationCase RunTube(const std::string& name,
  const std::string& slug,
  vtkPolyData* surface,
  double reynolds,
  double cellsAcross,
  const fs::path& folder,
  const CfdVerificationOptions& options)
{
  CfdVerificationCase c;
  c.name = name;
  c.folder = (folder / slug).string();
  WriteMesh(surface, (folder / (slug + ".vtp")).string());

  CfdCaseOptions caseOptions;
  caseOptions.caseDirectory = c.folder;
  caseOptions.sourceName = "the generated " + name;
  caseOptions.surfaceName = "tube";
  caseOptions.viscosity = Viscosity;
  caseOptions.density = Density;
  const double d = 1e-3 * Diameter;
  const double velocity = reynolds * Viscosity / d;
  caseOptions.flowRate = velocity * Pi * d * d / 4.0;
  // Shah's correlation is for a uniform inlet; the curved tube develops from one as well.
  caseOptions.inletProfile = CfdInletProfile::Plug;
  caseOptions.cellSize = d / (options.cellsAcross > 0.0 ? options.cellsAcross : cellsAcross);
  caseOptions.iterations = options.iterations;
  caseOptions.processors = options.processors;
  const CfdCaseResult written = WriteOpenFoamCase(surface, caseOptions);
  c.cellSize = written.cellSize;

  const CfdFlowResults flow = RunLabelledCase(c.folder, name, options.onLine, options.progress);
  c.iterations = flow.run.iterations;
  c.converged = flow.run.converged;
  c.cells = flow.meshCells;
  for (const CfdEndFlow& end : flow.ends)
  {
    if (end.role == PatchType::Outlet)
    {
      c.pressureDrop = end.pressureDropPa;
    }
  }
  return c;
}

std::vector<CfdWallSample> WallOf(const CfdVerificationCase& c)
{
  return ReadCfdWallSamples((fs::path(c.folder) / kCfdResultsFolder / kCfdSurfaceResults).string());
}

CfdVerificationCase StraightTube(const fs::path& folder, const CfdVerificationOptions& options)
{
  const double radius = 0.5 * Diameter;
  const auto surface =
    SweepClosedTube(StraightCentreline(StraightLength, 0.5 * radius), radius, Sides);
  CfdVerificationCase c = RunTube("straight tube",
    "straight-tube",
    surface,
    StraightReynolds,
    StraightCellsAcross,
    folder,
    options);
  const double d = 1e-3 * Diameter, length = 1e-3 * StraightLength;
  const double velocity = StraightReynolds * Viscosity / d;
  c.description = "D " + Short(Diameter) + " mm, L " + Short(StraightLength) + " mm, Re " +
    Short(StraightReynolds) + ", uniform inlet " + Short(velocity) + " m/s";

  c.figures.push_back({ "pressure drop",
    "Pa",
    c.pressureDrop,
    ShahPressureDrop(length, d, velocity, Viscosity, Density),
    "Shah 1978, developing flow, x+ " + Short(length / (d * StraightReynolds)),
    0.03 });

  const std::vector<CfdWallSample> wall = WallOf(c);
  const auto developed = [](const CfdWallSample& s)
  { return s.centroid.x >= DevelopedFrom && s.centroid.x <= DevelopedTo; };
  c.figures.push_back({ "wall shear stress, developed (" + Short(DevelopedFrom / Diameter) +
      " to " + Short(DevelopedTo / Diameter) + " D)",
    "Pa",
    MeanWallShear(wall, developed),
    PoiseuilleWallShearStress(d, velocity, Viscosity, Density),
    "Poiseuille 8 mu U / D",
    0.05 });
  return c;
}

CfdVerificationCase CurvedTube(const fs::path& folder, const CfdVerificationOptions& options)
{
  const double radius = 0.5 * Diameter;
  const auto surface =
    SweepClosedTube(ArcCentreline(BendRadius, BendAngle, 0.5 * radius), radius, Sides);
  CfdVerificationCase c = RunTube(
    "curved tube", "curved-tube", surface, CurvedReynolds, CurvedCellsAcross, folder, options);
  const double d = 1e-3 * Diameter;
  const double velocity = CurvedReynolds * Viscosity / d;
  const double dean = DeanNumber(CurvedReynolds, radius, BendRadius);
  c.description = "D " + Short(Diameter) + " mm, bend radius " + Short(BendRadius) + " mm, " +
    Short(BendAngle * 180.0 / Pi) + " degrees, Re " + Short(CurvedReynolds) + ", Dean " +
    Short(dean) + ", uniform inlet " + Short(velocity) + " m/s";

  // The angle of a wall point about the bend's centre (0, Rc, 0), from the inlet; its
  // centreline abscissa Rc x angle (m).
  const auto angle = [](const Vec3& p)
  {
    const double a = std::atan2(p.x, BendRadius - p.y);
    return a < 0.0 ? a + 2.0 * Pi : a;
  };
  const std::vector<CfdWallSample> wall = WallOf(c);
  const double gradient = -WallPressureSlope(
    wall,
    [&angle](const CfdWallSample& s) { return 1e-3 * BendRadius * angle(s.centroid); },
    [&angle](const CfdWallSample& s)
    {
      const double a = angle(s.centroid);
      return a >= CurvedFrom && a <= CurvedTo;
    });
  c.figures.push_back({ "friction ratio f_curved / f_straight, developed (" +
      Short(CurvedFrom * 180.0 / Pi) + " to " + Short(CurvedTo * 180.0 / Pi) + " degrees)",
    "",
    gradient / PoiseuillePressureGradient(d, velocity, Viscosity, Density),
    WhiteFrictionRatio(dean),
    "White 1929 at Dean " + Short(dean),
    0.10 });
  return c;
}

nlohmann::ordered_json FigureJson(const CfdVerificationFigure& f)
{
  nlohmann::ordered_json j;
  j["name"] = f.name;
  j["unit"] = f.unit;
  j["value"] = f.value;
  j["reference"] = f.reference;
  j["source"] = f.source;
  j["deviationPercent"] = 100.0 * f.Deviation();
  j["tolerancePercent"] = 100.0 * f.tolerance;
  j["passed"] = f.Passed();
  return j;
}

} // namespace

double CfdVerificationFigure::Deviation() const
{
  return this->reference != 0.0 ? this->value / this->reference - 1.0 : 0.0;
}

bool CfdVerificationFigure::Passed() const
{
  return std::isfinite(this->value) && this->reference != 0.0 &&
    std::fabs(this->Deviation()) <= this->tolerance;
}

bool CfdVerificationResult::Passed() const
{
  for (const CfdVerificationCase& c : this->cases)
  {
    for (const CfdVerificationFigure& f : c.figures)
    {
      if (!f.Passed())
      {
        return false;
      }
    }
  }
  return !this->cases.empty();
}

CfdVerificationResult RunCfdVerification(const CfdVerificationOptions& options)
{
  if (options.cellsAcross != 0.0 && !(options.cellsAcross >= 4.0 && options.cellsAcross <= 200.0))
  {
    throw InputError("--cells-across " + Short(options.cellsAcross) + ": give 4 to 200");
  }
  if (!options.straight && !options.curved)
  {
    throw InputError("no verification case chosen");
  }
  if (const std::string problem = FindOpenFoamProblem(options.processors); !problem.empty())
  {
    throw EnvironmentError(problem);
  }
  CasesFolder folder(options.folder);
  CfdVerificationResult result;
  if (options.straight)
  {
    result.cases.push_back(StraightTube(folder.Path, options));
  }
  if (options.curved)
  {
    result.cases.push_back(CurvedTube(folder.Path, options));
  }
  if (folder.Temporary)
  {
    for (CfdVerificationCase& c : result.cases)
    {
      c.folder.clear();
    }
  }
  return result;
}

std::string FormatCfdVerification(const CfdVerificationResult& result)
{
  std::string text;
  for (const CfdVerificationCase& c : result.cases)
  {
    text += c.name + ": " + c.description + "; " + std::to_string(c.cells) + " cells (wall cells " +
      Short(1e3 * c.cellSize) + " mm), " + std::to_string(c.iterations) + " iterations" +
      (c.converged ? ", converged" : ", not converged") + "\n";
    for (const CfdVerificationFigure& f : c.figures)
    {
      const std::string unit = f.unit.empty() ? "" : " " + f.unit;
      char line[512];
      std::snprintf(line,
        sizeof line,
        "  %s: %s%s against %s%s (%s): %+.2f %%, tolerance %.0f %%: %s\n",
        f.name.c_str(),
        Short(f.value, 4).c_str(),
        unit.c_str(),
        Short(f.reference, 4).c_str(),
        unit.c_str(),
        f.source.c_str(),
        100.0 * f.Deviation(),
        100.0 * f.tolerance,
        f.Passed() ? "pass" : "FAIL");
      text += line;
    }
  }
  text += result.Passed() ? "verification passed\n" : "verification FAILED\n";
  return text;
}

std::string CfdVerificationToJson(const CfdVerificationResult& result)
{
  nlohmann::ordered_json j;
  j["format"] = "bender-cfd-verification";
  j["version"] = 1;
  j["cases"] = nlohmann::ordered_json::array();
  for (const CfdVerificationCase& c : result.cases)
  {
    nlohmann::ordered_json cj;
    cj["name"] = c.name;
    cj["description"] = c.description;
    if (!c.folder.empty())
    {
      cj["folder"] = c.folder;
    }
    cj["cellSize_m"] = c.cellSize;
    cj["meshCells"] = c.cells;
    cj["iterations"] = c.iterations;
    cj["converged"] = c.converged;
    cj["figures"] = nlohmann::ordered_json::array();
    for (const CfdVerificationFigure& f : c.figures)
    {
      cj["figures"].push_back(FigureJson(f));
    }
    j["cases"].push_back(cj);
  }
  j["passed"] = result.Passed();
  return j.dump(2);
}

} // namespace bender
