#ifndef bender_WarpPlan_h
#define bender_WarpPlan_h

#include "Vec3.h"

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

/// A plan: warps applied in order (warp-file-format.md).
struct WarpPlan
{
  std::string units = "mm";
  std::vector<WarpSpec> warps;
  /// Unknown top-level fields, kept verbatim (name -> JSON text).
  std::map<std::string, std::string> extraFields;
};

} // namespace bender

#endif
