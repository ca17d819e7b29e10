#include "RibbonLengthChange.h"

#include "GeometryErrors.h"
#include "Ribbon.h"

#include <cmath>
#include <sstream>
#include <tuple>
#include <utility>

namespace bender
{

namespace
{
// The initial and the final wire's lengths (mm).
std::pair<double, double> WireLengths(const WarpSpec& warp)
{
  return { Ribbon(warp.initial).Wire().Length(), Ribbon(warp.final).Wire().Length() };
}
} // namespace

double RibbonLengthChange(const WarpSpec& warp)
{
  const auto [before, after] = WireLengths(warp);
  return after / before - 1.0;
}

std::string RibbonLengthNote(const WarpSpec& warp)
{
  double before = 0.0;
  double after = 0.0;
  try
  {
    std::tie(before, after) = WireLengths(warp);
  }
  catch (const GeometryError&)
  {
    return {};
  }
  const double change = after / before - 1.0;
  if (!(std::abs(change) > NotableRibbonLengthChange))
  {
    return {};
  }
  std::ostringstream text;
  text.setf(std::ios::fixed);
  text.precision(0);
  text << "the ribbon is " << std::abs(change) * 100.0 << " % "
       << (change < 0.0 ? "shorter" : "longer");
  text.precision(1);
  text << " (" << before << " -> " << after << " mm): the vessel is "
       << (change < 0.0 ? "compressed" : "stretched") << " along it";
  return text.str();
}

} // namespace bender
