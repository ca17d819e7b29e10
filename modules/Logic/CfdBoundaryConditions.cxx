#include "CfdBoundaryConditions.h"

#include "BenderErrors.h"
#include "CfdDictionaries.h"
#include "CfdMeshGrading.h"
#include "CfdPatches.h"
#include "Vec3.h"

#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <locale>
#include <map>
#include <sstream>
#include <utility>

namespace bender
{

std::string CfdInletProfileName(CfdInletProfile profile)
{
  return profile == CfdInletProfile::Poiseuille ? "poiseuille" : "plug";
}

std::string CfdOutletConditionName(CfdOutletCondition condition)
{
  switch (condition)
  {
    case CfdOutletCondition::Split:
      return "split";
    case CfdOutletCondition::Murray:
      return "murray";
    case CfdOutletCondition::Resistance:
      return "resistance";
    case CfdOutletCondition::ZeroPressure:
      break;
  }
  return "zero-pressure";
}

namespace
{

Vec3 PointOf(vtkPoints* points, vtkIdType id)
{
  double x[3];
  points->GetPoint(id, x);
  return { x[0], x[1], x[2] };
}

/// Distance from p to the segment [a, b].
double SegmentDistance(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double length2 = Dot(ab, ab);
  const double t = length2 > 0.0 ? std::clamp(Dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
  return Norm(p - (a + t * ab));
}

/// A field of 0/: the header, `head` (dimensions, internal field), then each patch's boundary
/// condition as `condition` writes it.
std::string InitialField(const std::string& cls,
  const std::string& object,
  const std::string& head,
  const std::vector<CfdPatch>& patches,
  const std::function<std::string(const CfdPatch&)>& condition)
{
  std::string s = CfdFoamHeader(cls, "0", object) + head + "boundaryField\n{\n";
  for (const auto& p : patches)
  {
    s += "    " + p.name + "\n    {\n" + condition(p) + "    }\n";
  }
  return s + "}\n";
}

const CfdOutletSetting* FindOutlet(const CfdCaseResult& r, const std::string& name)
{
  for (const CfdOutletSetting& o : r.outlets)
  {
    if (o.name == name)
    {
      return &o;
    }
  }
  return nullptr;
}

std::string OptionOf(CfdOutletCondition condition)
{
  return condition == CfdOutletCondition::Resistance ? "--resistance" : "--split";
}

/// outletValues as a value per outlet: every outlet once, no other name, values finite > 0.
std::map<std::string, double> ValuePerOutlet(const std::vector<CfdPatch>& patches,
  const CfdCaseOptions& options)
{
  const std::string option = OptionOf(options.outlets);
  std::string outlets;
  for (const CfdPatch& p : patches)
  {
    if (p.type == PatchType::Outlet)
    {
      outlets += (outlets.empty() ? "" : ", ") + p.name;
    }
  }
  std::map<std::string, double> values;
  for (const CfdOutletValue& v : options.outletValues)
  {
    const auto patch = std::find_if(
      patches.begin(), patches.end(), [&](const CfdPatch& p) { return p.name == v.name; });
    if (patch == patches.end() || patch->type != PatchType::Outlet)
    {
      throw InputError(option + " " + v.name + ": " +
        (patch == patches.end() ? "no such outlet" : "not an outlet") + " (outlets: " + outlets +
        ")");
    }
    if (!std::isfinite(v.value) || v.value <= 0.0)
    {
      throw InputError(option + " " + v.name + "=" + CfdShort(v.value) + ": give a value > 0");
    }
    if (!values.emplace(v.name, v.value).second)
    {
      throw InputError(option + " " + v.name + ": given twice");
    }
  }
  for (const CfdPatch& p : patches)
  {
    if (p.type == PatchType::Outlet && values.count(p.name) == 0)
    {
      throw InputError(option + ": give a value for every outlet (" + p.name +
        " has none; outlets: " + outlets + ")");
    }
  }
  return values;
}

} // namespace

CfdInletProfileData PoiseuilleInletProfile(vtkPolyData* surface,
  const std::vector<int>& cellIds,
  const CfdInletFlow& inlet,
  const std::string& name)
{
  // The cap's triangles (fans of its polygons) and its rim: the edges of one cap triangle only.
  std::vector<std::array<vtkIdType, 3>> triangles;
  vtkCellArray* polys = surface->GetPolys();
  vtkNew<vtkIdList> ids;
  polys->InitTraversal();
  for (std::size_t cell = 0; polys->GetNextCell(ids); ++cell)
  {
    if (cell < cellIds.size() && cellIds[cell] == inlet.id)
    {
      for (vtkIdType k = 1; k + 1 < ids->GetNumberOfIds(); ++k)
      {
        triangles.push_back({ ids->GetId(0), ids->GetId(k), ids->GetId(k + 1) });
      }
    }
  }
  std::map<std::pair<vtkIdType, vtkIdType>, int> edges;
  std::map<vtkIdType, std::size_t> local;
  for (const auto& t : triangles)
  {
    for (std::size_t k = 0; k < 3; ++k)
    {
      const vtkIdType a = t[k], b = t[(k + 1) % 3];
      ++edges[{ std::min(a, b), std::max(a, b) }];
      local.emplace(a, local.size());
    }
  }
  std::vector<std::pair<Vec3, Vec3>> rim;
  vtkPoints* points = surface->GetPoints();
  for (const auto& [edge, count] : edges)
  {
    if (count == 1)
    {
      rim.emplace_back(1e-3 * PointOf(points, edge.first), 1e-3 * PointOf(points, edge.second));
    }
  }
  if (triangles.empty() || rim.empty())
  {
    throw InputError(name + ": the inlet has " +
      (triangles.empty() ? std::string("no triangle") : std::string("no rim")) +
      ", no inlet profile can be laid on it");
  }

  // The samples: the cap's vertices and its triangles' centroids (metres); each triangle is
  // three (two corners and the centroid), on which the profile is linear.
  std::vector<Vec3> x(local.size());
  for (const auto& [id, i] : local)
  {
    x[i] = 1e-3 * PointOf(points, id);
  }
  std::vector<std::array<std::size_t, 3>> pieces;
  for (const auto& t : triangles)
  {
    const std::size_t a = local[t[0]], b = local[t[1]], c = local[t[2]], g = x.size();
    x.push_back((1.0 / 3.0) * (x[a] + x[b] + x[c]));
    pieces.push_back({ a, b, g });
    pieces.push_back({ b, c, g });
    pieces.push_back({ c, a, g });
  }
  // The distance of each sample to the rim, then the profile's shape 2 s - s^2.
  std::vector<double> shape(x.size(), 0.0);
  double farthest = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    double d = std::numeric_limits<double>::infinity();
    for (const auto& [a, b] : rim)
    {
      d = std::min(d, SegmentDistance(x[i], a, b));
    }
    shape[i] = d;
    farthest = std::max(farthest, d);
  }
  if (!(farthest > 0.0))
  {
    throw InputError(name + ": the inlet has no interior, no inlet profile can be laid on it");
  }
  for (double& f : shape)
  {
    const double s = f / farthest;
    f = 2.0 * s - s * s;
  }
  // The flow of the shape: each piece's area x the mean of its corners.
  double integral = 0.0, area = 0.0;
  for (const auto& [a, b, c] : pieces)
  {
    const double pieceArea = 0.5 * Norm(Cross(x[b] - x[a], x[c] - x[a]));
    area += pieceArea;
    integral += pieceArea * (shape[a] + shape[b] + shape[c]) / 3.0;
  }
  CfdInletProfileData profile;
  // OpenFOAM takes each face's value at its centre: on faces of h the midpoint rule gives a
  // parabola of half-width R a flow h^2 / (3 R^2) too large; the samples are lowered by as much.
  profile.faceCorrection =
    1.0 / (1.0 + inlet.faceSize * inlet.faceSize / (3.0 * farthest * farthest));
  const double peak = profile.faceCorrection * inlet.flowRate / integral;
  const Vec3 inward =
    -1.0 * Vec3{ inlet.outwardNormal[0], inlet.outwardNormal[1], inlet.outwardNormal[2] };
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    const Vec3 u = peak * shape[i] * inward;
    profile.points.push_back(ToArray(x[i]));
    profile.velocities.push_back(ToArray(u));
  }
  profile.flowRate = peak * integral;
  profile.area = area;
  profile.peakToMean = area / integral;
  profile.meanVelocity = ToArray((inlet.flowRate / area) * inward);
  return profile;
}

std::string BoundaryDataPoints(const CfdInletProfileData& profile)
{
  std::string s =
    "// The inlet cap's vertices and triangle centroids (m), where its profile is given.\n" +
    std::to_string(profile.points.size()) + "\n(\n";
  for (const auto& p : profile.points)
  {
    s += CfdVector(p) + "\n";
  }
  return s + ")\n";
}

std::string BoundaryDataVelocity(const CfdInletProfileData& profile)
{
  std::string s =
    "// The developed (Poiseuille) velocity at each point (m/s): " + CfdNumber(profile.flowRate) +
    " m^3/s on the cap, the flow x " + CfdNumber(profile.faceCorrection) +
    " (the faces' midpoint rule adds it back).\n" + std::to_string(profile.velocities.size()) +
    "\n(\n";
  for (const auto& u : profile.velocities)
  {
    s += CfdVector(u) + "\n";
  }
  // Read only where 0/U says setAverage true: the Allrun's mesh step replaces it with the mean
  // that carries the flow on the meshed inlet (here: the flow over the cap's area).
  return s + ")\n" + kCfdInletAverageMarker + "\n" + CfdVector(profile.meanVelocity) + "\n";
}

std::vector<CfdOutletSetting> CfdOutletSettings(const std::vector<CfdPatch>& patches,
  const CfdCaseOptions& options,
  double inletFlowRate)
{
  const CfdOutletCondition condition = options.outlets;
  const bool valued =
    condition == CfdOutletCondition::Split || condition == CfdOutletCondition::Resistance;
  if (!valued && !options.outletValues.empty())
  {
    throw InputError(OptionOf(CfdOutletCondition::Split) + "/--resistance: not with --outlets " +
      CfdOutletConditionName(condition));
  }
  const std::map<std::string, double> values =
    valued ? ValuePerOutlet(patches, options) : std::map<std::string, double>{};
  std::vector<CfdOutletSetting> outlets;
  double total = 0.0;
  for (const CfdPatch& p : patches)
  {
    if (p.type != PatchType::Outlet)
    {
      continue;
    }
    CfdOutletSetting o;
    o.name = p.name;
    if (condition == CfdOutletCondition::Split)
    {
      o.percent = values.at(p.name);
    }
    else if (condition == CfdOutletCondition::Murray)
    {
      o.percent = std::pow(0.5 * p.diameter, 3);
    }
    else if (condition == CfdOutletCondition::Resistance)
    {
      o.resistance = values.at(p.name);
      o.pressureReference = false;
    }
    total += o.percent;
    outlets.push_back(o);
  }
  if (condition != CfdOutletCondition::Split && condition != CfdOutletCondition::Murray)
  {
    return outlets;
  }
  if (condition == CfdOutletCondition::Split && std::abs(total - 100.0) > 0.1)
  {
    throw InputError("--split: the outlets' shares sum to " + CfdShort(total, 4) +
      " %, give shares summing to 100");
  }
  if (!(total > 0.0))
  {
    throw InputError("--outlets murray: the outlets have no area");
  }
  std::size_t largest = 0;
  for (std::size_t i = 0; i < outlets.size(); ++i)
  {
    outlets[i].percent *= 100.0 / total;
    outlets[i].flowRate = inletFlowRate * outlets[i].percent / 100.0;
    outlets[i].pressureReference = false;
    if (outlets[i].percent > outlets[largest].percent)
    {
      largest = i;
    }
  }
  outlets[largest].pressureReference = true;
  return outlets;
}

std::vector<CfdOutletValue> ParseCfdOutletValues(const std::string& option,
  const std::vector<std::string>& items)
{
  std::vector<CfdOutletValue> values;
  for (const std::string& item : items)
  {
    const std::size_t equals = item.find('=');
    CfdOutletValue v;
    v.name = item.substr(0, equals);
    std::istringstream number(equals == std::string::npos ? "" : item.substr(equals + 1));
    number.imbue(std::locale::classic());
    char rest = 0;
    if (equals == std::string::npos || v.name.empty() || !(number >> v.value) || number >> rest)
    {
      throw InputError(option + " " + item + ": give NAME=VALUE (outlet_1=60)");
    }
    values.push_back(v);
  }
  return values;
}

std::string VelocityField(const CfdCaseResult& r, const CfdCaseOptions& options)
{
  return InitialField("volVectorField",
    "U",
    "dimensions      [0 1 -1 0 0 0 0];\n\ninternalField   uniform (0 0 0);\n\n",
    r.patches,
    [&](const CfdPatch& p) -> std::string
    {
      if (p.type == PatchType::Wall)
      {
        return "        type            noSlip;\n";
      }
      if (p.type == PatchType::Inlet && r.inletProfile == CfdInletProfile::Poiseuille)
      {
        return "        // A developed (Poiseuille) profile on the inlet's own shape, " +
          CfdNumber(r.inletFlowRate) + " m^3/s:\n        // constant/boundaryData/" + p.name +
          "/points and 0/U, interpolated onto the snapped faces.\n"
          "        type            timeVaryingMappedFixedValue;\n"
          "        offset          (0 0 0);\n"
          "        // Switched on by the Allrun's mesh step, with the average (the end of the\n"
          "        // boundaryData's 0/U) that carries the flow on the meshed inlet. No value: "
          "the\n"
          "        // profile is mapped when the field is read (postProcess measures it).\n"
          "        setAverage      false;\n";
      }
      if (p.type == PatchType::Inlet && options.velocity > 0.0)
      {
        return "        // Uniform, normal to the inlet, into the domain (m/s).\n"
               "        type            surfaceNormalFixedValue;\n        refValue        "
               "uniform " +
          CfdNumber(-options.velocity) + ";\n        value           uniform (0 0 0);\n";
      }
      if (p.type == PatchType::Inlet)
      {
        return "        type            flowRateInletVelocity;\n"
               "        volumetricFlowRate constant " +
          CfdNumber(r.inletFlowRate) +
          ";  // m^3/s\n        extrapolateProfile no;\n        value           uniform (0 0 "
          "0);\n";
      }
      const CfdOutletSetting* o = FindOutlet(r, p.name);
      if (o && o->flowRate > 0.0 && !o->pressureReference)
      {
        return "        // " + CfdShort(o->percent, 4) +
          " % of the inlet's flow (m^3/s).\n        type            flowRateOutletVelocity;\n"
          "        volumetricFlowRate constant " +
          CfdNumber(o->flowRate) + ";\n        value           uniform (0 0 0);\n";
      }
      return "        type            inletOutlet;\n        inletValue      uniform (0 0 0);\n"
             "        value           uniform (0 0 0);\n";
    });
}

std::string PressureField(const CfdCaseResult& r)
{
  return InitialField("volScalarField",
    "p",
    "// Kinematic pressure p / rho (m^2/s^2).\ndimensions      [0 2 -2 0 0 0 0];\n\n"
    "internalField   uniform 0;\n\n",
    r.patches,
    [&](const CfdPatch& p) -> std::string
    {
      const CfdOutletSetting* o = p.type == PatchType::Outlet ? FindOutlet(r, p.name) : nullptr;
      if (!o || (!o->pressureReference && o->resistance <= 0.0))
      {
        return "        type            zeroGradient;\n";
      }
      if (o->pressureReference)
      {
        return "        type            fixedValue;\n        value           uniform 0;\n";
      }
      return "        // Resistance p = R Q, R = " + CfdShort(o->resistance, 6) +
        " Pa s/m^3 (steady Windkessel):\n        // fanPressure's curve, "
        "constant/resistance/" +
        p.name +
        ".\n        type            fanPressure;\n        direction       out;\n"
        "        file            \"$FOAM_CASE/constant/resistance/" +
        p.name +
        "\";\n        outOfBounds     clamp;\n        p0              uniform 0;\n"
        "        value           uniform 0;\n";
    });
}

std::string ResistanceCurve(const CfdOutletSetting& outlet, double density, double inletFlowRate)
{
  const double q = 10.0 * inletFlowRate;
  return "// Outlet " + outlet.name + ": R = " + CfdNumber(outlet.resistance) +
    " Pa s/m^3, rho = " + CfdNumber(density) +
    " kg/m^3. (flow m^3/s, -R Q / rho m^2/s^2): fanPressure\n"
    "// sets p = p0 - curve(Q), so p = R Q / rho; held beyond the last point.\n(\n    (0 0)\n"
    "    (" +
    CfdNumber(q) + " " + CfdNumber(-outlet.resistance * q / density) + ")\n)\n";
}

std::string FormatCfdBoundaryConditions(const CfdCaseResult& r)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << "  inlet profile: "
    << (r.inletProfile == CfdInletProfile::Poiseuille
           ? "developed (Poiseuille on the inlet's shape), u_max / u_mean " +
             CfdShort(r.inletPeakToMean)
           : std::string("plug (uniform)"))
    << "\n  outlets: ";
  switch (r.outletCondition)
  {
    case CfdOutletCondition::ZeroPressure:
      s << "p = 0 at each (the split follows from the geometry)";
      break;
    case CfdOutletCondition::Split:
    case CfdOutletCondition::Murray:
      s << (r.outletCondition == CfdOutletCondition::Murray ? "Murray's law (Q ~ r^3)"
                                                            : "prescribed split");
      for (const CfdOutletSetting& o : r.outlets)
      {
        s << ", " << o.name << " " << CfdShort(o.percent) << " %"
          << (o.pressureReference ? " (p = 0, the rest of the flow)" : "");
      }
      break;
    case CfdOutletCondition::Resistance:
      s << "resistances p = R Q";
      for (const CfdOutletSetting& o : r.outlets)
      {
        s << ", " << o.name << " R " << CfdShort(o.resistance) << " Pa s/m^3";
      }
      break;
  }
  s << "\n" << FormatCfdMeshGrading(r.grading) << "  prism layers: ";
  if (r.layers > 0)
  {
    s << r.layers << " on the wall";
  }
  else
  {
    s << "none";
  }
  s << "\n";
  return s.str();
}

} // namespace bender
