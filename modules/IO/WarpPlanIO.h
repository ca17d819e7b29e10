#ifndef bender_WarpPlanIO_h
#define bender_WarpPlanIO_h

#include "BenderErrors.h"
#include "WarpPlan.h"

#include <nlohmann/json_fwd.hpp>

#include <stdexcept>
#include <string>

namespace bender
{

/// A plan file that breaks warp-file-format.md. what() is one line naming the source, the
/// warp index and the field: "plan.bender.json: warps[2].final.end.tangent: zero vector".
class WarpPlanError : public InputError
{
public:
  using InputError::InputError;
};

/// Parses and validates a plan (structure, ranges, and every warp's validity under the
/// spec's convention 11 through RibbonWarp::Validate). sourceName prefixes messages ("plan"
/// when empty). One bad warp rejects the whole plan.
///
/// Vectors are kept exactly as written (not normalised here): the geometry core normalises
/// tangents and orthonormalises normals (spec 2), so a replay computes from the very numbers
/// the writing session had. Unknown fields at the top level and in each warp are kept in
/// extraFields as compact JSON text (members in their original order); unknown fields inside
/// the known objects (ribbons, ends, decay, subdivision) are ignored. Malformed JSON gives
/// "source: malformed JSON: parse error at line L, column C: ..."; nesting deeper than 64
/// levels is refused.
WarpPlan ParseWarpPlan(const std::string& jsonText, const std::string& sourceName);
/// Reads and validates a plan file.
WarpPlan ReadWarpPlan(const std::string& path);
/// Serialises a plan: every field written (defaults too), numbers as the shortest decimal
/// that reads back as the same double (at most 17 significant digits, locale-independent),
/// unknown fields written back after the known ones. Throws WarpPlanError ("plan: <field>:
/// ...") for a non-finite number (JSON cannot hold it), an extra field that is not valid JSON
/// or that has the name of a known field. Does not run the geometry validation.
std::string SerializeWarpPlan(const WarpPlan& plan);
/// The plan as its JSON object (the members SerializeWarpPlan writes, in the same order), for
/// documents that embed a plan (the session autosave). Throws WarpPlanError as
/// SerializeWarpPlan does, prefixed with sourceName ("plan" when empty).
nlohmann::ordered_json WarpPlanToJson(const WarpPlan& plan, const std::string& sourceName = "");
/// Validates a plan given as a JSON object, as ParseWarpPlan does its text.
WarpPlan WarpPlanFromJson(const nlohmann::ordered_json& document, const std::string& sourceName);
/// Writes a plan atomically (temporary file flushed to disk, then renamed over path; nothing
/// changes at path on failure). Throws WarpPlanError naming the file's base name.
void WriteWarpPlan(const WarpPlan& plan, const std::string& path);

} // namespace bender

#endif
