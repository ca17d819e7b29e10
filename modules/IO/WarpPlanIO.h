#ifndef bender_WarpPlanIO_h
#define bender_WarpPlanIO_h

#include "WarpPlan.h"

#include <stdexcept>
#include <string>

namespace bender
{

/// A plan file that breaks warp-file-format.md. what() is one line naming the source, the
/// warp index and the field: "plan.bender.json: warps[2].final.end.tangent: zero vector".
class WarpPlanError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Parses and validates a plan (structure, ranges, and every warp's validity under the
/// spec's convention 11 through RibbonWarp::Validate). sourceName prefixes messages.
WarpPlan ParseWarpPlan(const std::string& jsonText, const std::string& sourceName);
/// Reads and validates a plan file.
WarpPlan ReadWarpPlan(const std::string& path);
/// Serialises a plan (positions with 17 significant digits, unknown fields kept).
std::string SerializeWarpPlan(const WarpPlan& plan);
/// Writes a plan atomically (temporary file, then rename).
void WriteWarpPlan(const WarpPlan& plan, const std::string& path);

} // namespace bender

#endif
