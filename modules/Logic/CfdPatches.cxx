#include "CfdPatches.h"

#include "BenderErrors.h"

#include <cmath>

namespace bender
{

namespace
{
constexpr double kPi = 3.14159265358979323846;
} // namespace

bool IsEndPatch(PatchType type)
{
  return type != PatchType::Wall;
}

std::vector<CfdPatch> CfdPatchesOf(const PatchSidecar& measured, const std::string& name)
{
  if (!(measured.volume > 0.0) || !std::isfinite(measured.volume))
  {
    throw InputError(name + ": the surface encloses no volume");
  }
  std::vector<CfdPatch> patches;
  for (const PatchGeometry& g : measured.patches)
  {
    CfdPatch p;
    p.name = g.label.name;
    p.type = g.label.type;
    p.triangles = static_cast<long long>(g.triangles);
    p.area = g.area * 1e-6;
    if (g.area > 0.0)
    {
      for (std::size_t k = 0; k < 3; ++k)
      {
        p.centre[k] = 1e-3 * g.areaMoment[k] / g.area;
      }
    }
    // Every patch's own direction, the wall's too (its area vectors nearly cancel).
    const double norm = std::sqrt(g.vectorArea[0] * g.vectorArea[0] +
      g.vectorArea[1] * g.vectorArea[1] + g.vectorArea[2] * g.vectorArea[2]);
    if (norm > 0.0)
    {
      for (std::size_t k = 0; k < 3; ++k)
      {
        p.normal[k] = g.vectorArea[k] / norm;
      }
    }
    p.diameter = 2.0 * std::sqrt(p.area / kPi);
    patches.push_back(p);
  }
  return patches;
}

std::array<double, 3> InsidePoint(const PatchSidecar& measured,
  double cellSize,
  const std::string& name)
{
  if (!measured.hasInsidePoint)
  {
    throw InputError(name +
      ": no point inside the lumen was found behind its ends (is the "
      "surface oriented consistently and closed?)");
  }
  // Metres, nudged off the background grid's planes (a fraction of a cell: far less than the
  // point's distance to the wall).
  std::array<double, 3> x{};
  for (std::size_t k = 0; k < 3; ++k)
  {
    x[k] = 1e-3 * measured.insidePoint[k] + (0.0173 + 0.0119 * static_cast<double>(k)) * cellSize;
  }
  return x;
}

} // namespace bender
