#ifndef bender_WarpPlan_h
#define bender_WarpPlan_h

#include "Vec3.h"

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bender
{

/// One end of a ribbon: the wire's end point, its tangent (direction of travel from the
/// start towards the end, at both ends) and the ribbon normal. Not necessarily unit or
/// orthogonal as given; the geometry core normalises (spec 2).
struct RibbonEnd
{
  Vec3 position;
  Vec3 tangent{ 1, 0, 0 };
  Vec3 normal{ 0, 0, 1 };
};

/// A ribbon as the user holds it: two end frames and the whole turns of twist added to
/// the principal twist (spec 2.1, normative convention 4).
struct RibbonSpec
{
  RibbonEnd start;
  RibbonEnd end;
  int extraTurns = 0;
};

/// True when the two ribbons are exactly the same: every coordinate of both end frames and the
/// extra turns (a release without motion, a ribbon that an autosave already keeps).
inline bool SameRibbon(const RibbonSpec& a, const RibbonSpec& b)
{
  auto same = [](const RibbonEnd& x, const RibbonEnd& y)
  {
    auto eq = [](const Vec3& u, const Vec3& v) { return u.x == v.x && u.y == v.y && u.z == v.z; };
    return eq(x.position, y.position) && eq(x.tangent, y.tangent) && eq(x.normal, y.normal);
  };
  return same(a.start, b.start) && same(a.end, b.end) && a.extraTurns == b.extraTurns;
}

enum class DecayShape
{
  Bell,   ///< (1 - x^2)^3
  Plateau ///< 1 up to p, then a C2 fall-off (spec 5)
};

struct DecaySpec
{
  DecayShape shape = DecayShape::Bell;
  double plateau = 0.5; ///< plateau width p as a fraction of R, [0, 0.95]; ignored for Bell
};

struct SubdivisionSpec
{
  double tolerance = 0.0; ///< length units, > 0
  int maxPasses = 8;      ///< >= 0
};

/// One warp of a plan: the ribbon at grab and at release plus the warp's parameters.
struct WarpSpec
{
  RibbonSpec initial;
  RibbonSpec final;
  double radius = 1.0; ///< R, radius of the region of influence around the initial wire, > 0
  DecaySpec decay;
  bool reverseScrews = false;
  std::optional<SubdivisionSpec> subdivision;
  /// Unknown fields of this warp's JSON object, kept verbatim (name -> JSON text).
  std::map<std::string, std::string> extraFields;
};

/// One vessel end of a Prepare for CFD step: where it is cut (bender::ClipEndRequest).
struct CfdStepEnd
{
  Vec3 position;          ///< near the vessel end (distance >= 0) or the cut (distance < 0)
  double distance = -1.0; ///< along the centerline from the end; < 0: at the point nearest position
};

/// The name of the end nearest `position` (bender::CfdEndName).
struct CfdStepName
{
  Vec3 position;
  std::string name;   ///< a valid patch name, not "wall"
  bool inlet = false; ///< this end is the inlet (also when the name is "inlet")
};

/// The flow-extension factor of the end nearest `position` (bender::CfdEndFactor).
struct CfdStepFactor
{
  Vec3 position;
  double factor = 0.0; ///< extension length / radius, [0, 100]
};

/// A Prepare for CFD step of a plan (bender::PrepareForCfd: the ends clipped perpendicular to
/// the centerlines computed from the surface, named, extended and capped), applied after the
/// first `afterWarps` warps. The same options on the same surface give the same surface.
struct CfdStep
{
  std::size_t afterWarps = 0; ///< applied before warps[afterWarps], in [0, warps.size()]
  bool clip = true;           ///< off: the surface's open ends as they are
  bool cap = true;
  std::vector<CfdStepEnd> ends; ///< ends with a chosen cut; the others at the default
  std::vector<CfdStepName> names;
  double inletExtension = 10.0; ///< flow-extension factors, [0, 100]
  double outletExtension = 5.0;
  std::vector<CfdStepFactor> extensionFactors; ///< per end, by position
  /// Unknown fields of this step's JSON object, kept verbatim (name -> JSON text).
  std::map<std::string, std::string> extraFields;
};

/// A plan: warps applied in order, with Prepare for CFD steps between them
/// (warp-file-format.md; the steps: docs/ribbon-warp.md, "Plan files").
struct WarpPlan
{
  std::string units = "mm";
  std::vector<WarpSpec> warps;
  /// In the order applied (afterWarps never decreasing).
  std::vector<CfdStep> cfdSteps;
  /// Unknown top-level fields, kept verbatim (name -> JSON text).
  std::map<std::string, std::string> extraFields;
};

/// One step of a plan: a warp (warps[index]) or a Prepare for CFD step (cfdSteps[index]).
struct PlanStepRef
{
  bool cfd = false;
  std::size_t index = 0;
};

/// The steps of `plan` in the order they are applied: each CFD step before the warp its
/// afterWarps names (after the last warp when afterWarps is warps.size() or more).
inline std::vector<PlanStepRef> PlanOrder(const WarpPlan& plan)
{
  std::vector<PlanStepRef> order;
  std::size_t next = 0;
  for (std::size_t w = 0; w < plan.warps.size(); ++w)
  {
    for (; next < plan.cfdSteps.size() && plan.cfdSteps[next].afterWarps <= w; ++next)
    {
      order.push_back({ true, next });
    }
    order.push_back({ false, w });
  }
  for (; next < plan.cfdSteps.size(); ++next)
  {
    order.push_back({ true, next });
  }
  return order;
}

} // namespace bender

#endif
