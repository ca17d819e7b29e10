#include "SweepCandidates.h"

#include "BenderErrors.h"
#include "Quaternion.h"
#include "Screw.h"

#include <algorithm>
#include <cmath>
#include <locale>
#include <sstream>

namespace bender
{

std::string SweepParameterName(SweepParameter parameter)
{
  switch (parameter)
  {
    case SweepParameter::Fraction:
      return "fraction";
    case SweepParameter::Radius:
      return "radius";
    case SweepParameter::Plan:
      return "plan";
  }
  return "fraction";
}

namespace
{
// A number that is all of `text`; false otherwise.
bool ReadNumber(const std::string& text, double& value)
{
  std::istringstream in(text);
  in.imbue(std::locale::classic());
  in >> value;
  return !text.empty() && in && in.peek() == std::char_traits<char>::eof() && std::isfinite(value);
}

// The end's frame as the geometry core reads it (spec 2): unit tangent, normal made orthogonal
// to it and unit, binormal T x N.
Frame EndFrame(const RibbonEnd& end)
{
  const Vec3 t = Normalized(end.tangent);
  Frame frame = FrameOfTangentNormal(t, Normalized(end.normal - t * Dot(end.normal, t)));
  frame.origin = end.position;
  return frame;
}
} // namespace

SweepVary ParseSweepVary(const std::string& text)
{
  const std::string where = "--vary " + text;
  const auto equal = text.find('=');
  if (equal == std::string::npos)
  {
    throw InputError(where + ": expected NAME=FROM:TO:COUNT (fraction or radius)");
  }
  SweepVary vary;
  const std::string name = text.substr(0, equal);
  if (name == "fraction")
  {
    vary.parameter = SweepParameter::Fraction;
  }
  else if (name == "radius")
  {
    vary.parameter = SweepParameter::Radius;
  }
  else
  {
    throw InputError(where + ": unknown parameter '" + name + "' (fraction or radius)");
  }
  std::vector<std::string> parts;
  std::string rest = text.substr(equal + 1);
  for (std::size_t colon; (colon = rest.find(':')) != std::string::npos;)
  {
    parts.push_back(rest.substr(0, colon));
    rest = rest.substr(colon + 1);
  }
  parts.push_back(rest);
  double count = 0.0;
  if (parts.size() != 3 || !ReadNumber(parts[0], vary.from) || !ReadNumber(parts[1], vary.to) ||
    !ReadNumber(parts[2], count))
  {
    throw InputError(where + ": expected NAME=FROM:TO:COUNT, three numbers");
  }
  if (count != std::floor(count) || count < 1 || count > 1000)
  {
    throw InputError(where + ": COUNT must be a whole number in [1, 1000]");
  }
  vary.count = static_cast<int>(count);
  if (vary.count == 1 && vary.from != vary.to)
  {
    throw InputError(where + ": one value needs FROM = TO");
  }
  if (vary.parameter == SweepParameter::Fraction &&
    (vary.from < -2 || vary.from > 4 || vary.to < -2 || vary.to > 4))
  {
    throw InputError(where + ": a fraction must be in [-2, 4]");
  }
  if (vary.parameter == SweepParameter::Radius && (vary.from <= 0 || vary.to <= 0))
  {
    throw InputError(where + ": a radius must be > 0 mm");
  }
  return vary;
}

std::vector<double> SweepValues(const SweepVary& vary)
{
  std::vector<double> values;
  for (int i = 0; i < vary.count; ++i)
  {
    values.push_back(i + 1 == vary.count && vary.count > 1
        ? vary.to
        : vary.from + (vary.to - vary.from) * i / std::max(1, vary.count - 1));
  }
  return values;
}

RibbonEnd EndAtFraction(const RibbonEnd& initial, const RibbonEnd& final, double fraction)
{
  if (fraction == 0.0)
  {
    return initial;
  }
  if (fraction == 1.0)
  {
    return final;
  }
  const Frame c = EndFrame(initial);
  const Frame cp = EndFrame(final);
  // R = M' M^T, its quaternion q(M') q(M)*; the minimal screw (w >= 0).
  Quaternion q = QuaternionOfFrame(cp) * Conjugate(QuaternionOfFrame(c));
  if (q.w < 0.0)
  {
    q = -q;
  }
  const DualQuaternion motion = MotionBetween(c, cp, q);
  // The rotation part of motion^f: (cos hf, sin hf K) with q = (cos h, sin h K).
  const double sh = Norm(q.Vector());
  Quaternion rf;
  if (sh > 0.0)
  {
    const double hf = std::atan2(sh, q.w) * fraction;
    const Vec3 k = q.Vector() / sh;
    rf = { std::cos(hf), std::sin(hf) * k.x, std::sin(hf) * k.y, std::sin(hf) * k.z };
  }
  RibbonEnd end;
  end.position = ApplyScrewFraction(motion, c.origin, fraction);
  end.tangent = Normalized(RotateByQuaternion(rf, c.t));
  end.normal = Normalized(RotateByQuaternion(rf, c.n));
  return end;
}

WarpSpec WarpAtFraction(const WarpSpec& warp, double fraction)
{
  WarpSpec moved = warp;
  moved.final.start = EndAtFraction(warp.initial.start, warp.final.start, fraction);
  moved.final.end = EndAtFraction(warp.initial.end, warp.final.end, fraction);
  return moved;
}

namespace
{
std::string CandidateId(std::size_t index)
{
  const std::string number = std::to_string(index);
  return "c" + std::string(number.size() < 2 ? 2 - number.size() : 0, '0') + number;
}

WarpPlan WarpsOnly(const WarpPlan& plan)
{
  WarpPlan warps = plan;
  warps.cfdSteps.clear();
  return warps;
}

SweepCandidate Original(SweepParameter parameter, double value)
{
  SweepCandidate original;
  original.id = "original";
  original.parameter = parameter;
  original.value = value;
  original.original = true;
  return original;
}
} // namespace

std::vector<SweepCandidate> MakeSweepCandidates(const WarpPlan& plan,
  const std::string& planName,
  const SweepVary& vary)
{
  if (plan.warps.empty())
  {
    throw InputError(planName + ": the plan has no warp to vary");
  }
  std::vector<SweepCandidate> candidates;
  if (vary.parameter == SweepParameter::Radius)
  {
    candidates.push_back(Original(vary.parameter, 0.0));
  }
  const std::vector<double> values = SweepValues(vary);
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    SweepCandidate candidate;
    candidate.id = CandidateId(i);
    candidate.parameter = vary.parameter;
    candidate.value = values[i];
    candidate.planName = planName;
    candidate.plan = WarpsOnly(plan);
    for (WarpSpec& warp : candidate.plan.warps)
    {
      if (vary.parameter == SweepParameter::Fraction)
      {
        warp = WarpAtFraction(warp, values[i]);
      }
      else
      {
        warp.radius = values[i];
      }
    }
    candidate.original = vary.parameter == SweepParameter::Fraction && values[i] == 0.0;
    candidates.push_back(candidate);
  }
  return candidates;
}

std::vector<SweepCandidate> MakePlanCandidates(const std::vector<WarpPlan>& plans,
  const std::vector<std::string>& planNames)
{
  std::vector<SweepCandidate> candidates{ Original(SweepParameter::Plan, -1.0) };
  for (std::size_t i = 0; i < plans.size(); ++i)
  {
    const std::string name = i < planNames.size() ? planNames[i] : "plan";
    if (plans[i].warps.empty())
    {
      throw InputError(name + ": the plan has no warp");
    }
    SweepCandidate candidate;
    candidate.id = CandidateId(i);
    candidate.parameter = SweepParameter::Plan;
    candidate.value = static_cast<double>(i);
    candidate.planName = name;
    candidate.plan = WarpsOnly(plans[i]);
    candidates.push_back(candidate);
  }
  return candidates;
}

} // namespace bender
