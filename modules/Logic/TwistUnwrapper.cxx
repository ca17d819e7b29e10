#include "TwistUnwrapper.h"

#include "Ribbon.h"

#include <cmath>

namespace bender
{

namespace
{
constexpr double TwoPi = 6.283185307179586476925286766559;
}

void TwistUnwrapper::Start(const RibbonSpec& initial)
{
  this->Reference = Ribbon(initial).Twist();
}

RibbonSpec TwistUnwrapper::Unwrap(const RibbonSpec& next) const
{
  RibbonSpec result = next;
  result.extraTurns = 0;
  const double principal = Ribbon(result).PrincipalTwist();
  result.extraTurns = static_cast<int>(std::lround((this->Reference - principal) / TwoPi));
  return result;
}

void TwistUnwrapper::Accept(const RibbonSpec& unwrapped)
{
  this->Reference = Ribbon(unwrapped).Twist();
}

} // namespace bender
