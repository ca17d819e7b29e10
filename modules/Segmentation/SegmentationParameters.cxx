// The range checks of the segmentation parameters, apart from the segmentation itself so that
// what only checks parameters (the session file reader, its fuzzer) does not need ITK.

#include "VesselSegmentation.h"

#include <cmath>
#include <string>

namespace bender
{

namespace
{

void Require(bool ok, const std::string& message)
{
  if (!ok)
  {
    throw ParameterError("segmentation parameter " + message);
  }
}

} // namespace

void ValidateSegmentationParameters(const SegmentationParameters& p)
{
  Require(std::isfinite(p.lower) && !std::isnan(p.upper) && p.lower <= p.upper,
    "window: need finite lower <= upper");
  for (const Point3& s : p.seeds)
  {
    Require(std::isfinite(s[0]) && std::isfinite(s[1]) && std::isfinite(s[2]),
      "seeds: non-finite coordinate");
  }
  Require(p.closingRadius >= 0.0 && p.closingRadius <= 5.0, "closingRadius: must be in [0, 5] mm");
  Require(p.minRadius >= 0.1 && p.minRadius <= p.maxRadius && p.maxRadius <= 20.0,
    "vessel radii: need 0.1 <= minRadius <= maxRadius <= 20 mm");
  Require(p.scales >= 1 && p.scales <= 10, "scales: must be in [1, 10]");
  Require(p.alpha > 0.0 && p.alpha <= 2.0 && p.beta > 0.0 && p.beta <= 2.0 && p.gamma > 0.0,
    "alpha/beta/gamma: need alpha, beta in (0, 2] and gamma > 0");
  Require(p.vesselnessThreshold > 0.0 && p.vesselnessThreshold < 1.0,
    "vesselnessThreshold: must be in (0, 1)");
  Require(p.levelSetIterations >= 0 && p.levelSetIterations <= 1000,
    "levelSetIterations: must be in [0, 1000]");
  Require(p.levelSetSigma > 0.0 && p.levelSetSigma <= 5.0, "levelSetSigma: must be in (0, 5] mm");
  Require(p.levelSetPropagation >= -1.0 && p.levelSetPropagation <= 1.0,
    "levelSetPropagation: must be in [-1, 1]");
  Require(p.levelSetCurvature >= 0.0 && p.levelSetCurvature <= 5.0,
    "levelSetCurvature: must be in [0, 5]");
}

} // namespace bender
