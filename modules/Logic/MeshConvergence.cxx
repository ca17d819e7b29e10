#include "MeshConvergence.h"

#include "BenderErrors.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace bender
{
namespace
{

std::string Number(double v)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

// Celik's equation for the apparent order with monotone changes (s = 1), as g(p) = 0:
// g(p) = p ln r21 - ln(e32 / e21) - ln((r21^p - 1) / (r32^p - 1)). expm1 keeps small p exact.
double OrderEquation(double p, double r21, double r32, double changeRatio)
{
  return p * std::log(r21) - std::log(changeRatio) -
    std::log(std::expm1(p * std::log(r21)) / std::expm1(p * std::log(r32)));
}

constexpr double SmallestOrder = 1e-6;
constexpr double LargestOrder = 64.0;

// The root of OrderEquation in [SmallestOrder, LargestOrder] by bisection; <= 0 when there is
// none with a positive order (the changes do not shrink fast enough to converge), LargestOrder
// when the finest change is too small for any order up to it.
double SolveOrder(double r21, double r32, double changeRatio)
{
  double lo = SmallestOrder;
  if (OrderEquation(lo, r21, r32, changeRatio) >= 0.0)
  {
    return 0.0;
  }
  double hi = 1.0;
  while (OrderEquation(hi, r21, r32, changeRatio) < 0.0)
  {
    if (hi >= LargestOrder)
    {
      return LargestOrder;
    }
    lo = hi;
    hi = std::min(2.0 * hi, LargestOrder);
  }
  for (int i = 0; i < 200 && hi - lo > 1e-14 * hi; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (OrderEquation(mid, r21, r32, changeRatio) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

} // namespace

const char* ConvergenceKindName(ConvergenceKind kind)
{
  switch (kind)
  {
    case ConvergenceKind::Monotone:
      return "monotone";
    case ConvergenceKind::Oscillatory:
      return "oscillatory";
    case ConvergenceKind::Diverging:
      return "diverging";
    case ConvergenceKind::Unchanged:
      return "unchanged";
  }
  return "unknown";
}

std::optional<double> CoarsestDeviation(const MeshConvergence& study)
{
  // study.extrapolated holds the finest value where nothing is extrapolated.
  if (study.kind == ConvergenceKind::Diverging || study.extrapolated == 0.0)
  {
    return std::nullopt;
  }
  return (study.values[2] - study.extrapolated) / std::fabs(study.extrapolated);
}

MeshConvergence EstimateMeshConvergence(const std::array<MeshSample, 3>& samples)
{
  for (std::size_t i = 0; i < samples.size(); ++i)
  {
    const MeshSample& s = samples[i];
    if (!std::isfinite(s.cellSize) || !(s.cellSize > 0.0))
    {
      throw InputError("mesh " + std::to_string(i + 1) + ": cell size " + Number(s.cellSize) +
        " (give a finite size > 0)");
    }
    if (!std::isfinite(s.value))
    {
      throw InputError("mesh " + std::to_string(i + 1) + " (cell size " + Number(s.cellSize) +
        "): the value is not a number");
    }
  }
  std::array<MeshSample, 3> sorted = samples;
  std::sort(sorted.begin(),
    sorted.end(),
    [](const MeshSample& a, const MeshSample& b) { return a.cellSize < b.cellSize; });

  MeshConvergence c;
  for (std::size_t i = 0; i < 3; ++i)
  {
    c.cellSizes[i] = sorted[i].cellSize;
    c.values[i] = sorted[i].value;
  }
  c.ratio21 = c.cellSizes[1] / c.cellSizes[0];
  c.ratio32 = c.cellSizes[2] / c.cellSizes[1];
  for (const auto& [ratio, pair] : { std::pair{ c.ratio21, 0 }, std::pair{ c.ratio32, 1 } })
  {
    // A ratio written as 1.3 may come out a rounding below it.
    if (ratio < MinimumRefinementRatio * (1.0 - 1e-9))
    {
      throw InputError("cell sizes " + Number(c.cellSizes[pair]) + " and " +
        Number(c.cellSizes[pair + 1]) + ": refinement ratio " + Number(ratio) + ", give at least " +
        Number(MinimumRefinementRatio));
    }
  }

  const double f1 = c.values[0], f2 = c.values[1], f3 = c.values[2];
  const double e21 = f2 - f1, e32 = f3 - f2;
  // Changes below round-off of the values are no change.
  const double scale = std::max({ std::fabs(f1), std::fabs(f2), std::fabs(f3) });
  const double roundOff = 1e-12 * scale;
  const bool fineSame = std::fabs(e21) <= roundOff, coarseSame = std::fabs(e32) <= roundOff;
  c.extrapolated = f1;
  c.relativeError = f1 != 0.0 ? std::fabs(e21) / std::fabs(f1) : 0.0;
  if (fineSame)
  {
    c.kind = ConvergenceKind::Unchanged;
    c.relativeError = 0.0;
    c.note = coarseSame ? "the three values are equal: no order of convergence to measure"
                        : "the two finest values are equal: no order of convergence to measure";
    return c;
  }
  if (coarseSame)
  {
    c.kind = ConvergenceKind::Diverging;
    c.note = "the two coarsest values are equal but the finest differs: not converging";
    return c;
  }
  if ((e21 > 0.0) != (e32 > 0.0))
  {
    c.kind = ConvergenceKind::Oscillatory;
    c.uncertainty = 0.5 * (std::max({ f1, f2, f3 }) - std::min({ f1, f2, f3 }));
    c.note = "oscillatory convergence (the changes alternate in sign): no extrapolation, the "
             "values span +-" +
      Number(c.uncertainty);
    return c;
  }
  c.order = SolveOrder(c.ratio21, c.ratio32, e32 / e21);
  if (!(c.order > 0.0))
  {
    c.kind = ConvergenceKind::Diverging;
    c.order = 0.0;
    c.note = "the change on the finest mesh is not smaller than the refinement ratios allow "
             "for any positive order: not converging";
    return c;
  }
  c.kind = ConvergenceKind::Monotone;
  const double rp = std::pow(c.ratio21, c.order);
  c.extrapolated = std::isfinite(rp) ? (rp * f1 - f2) / (rp - 1.0) : f1;
  c.extrapolatedRelativeError =
    c.extrapolated != 0.0 ? std::fabs(c.extrapolated - f1) / std::fabs(c.extrapolated) : 0.0;
  c.uncertainty = std::isfinite(rp) ? GciSafetyFactor * std::fabs(e21) / (rp - 1.0) : 0.0;
  c.gci = f1 != 0.0 ? c.uncertainty / std::fabs(f1) : 0.0;
  c.note = "monotone convergence, apparent order " + Number(c.order);
  if (c.order >= LargestOrder)
  {
    c.note += " (or more: the finest change is negligible)";
  }
  if (f1 == 0.0)
  {
    c.note += "; the finest value is 0, so the GCI is given in the value's unit only";
  }
  return c;
}

} // namespace bender
