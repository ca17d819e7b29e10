#ifndef bender_WarpPlanFormat_h
#define bender_WarpPlanFormat_h

// The names and versions of the plan file (warp-file-format.md) that its reader
// (WarpPlanIO.cxx) and its writer (WarpPlanWriter.cxx) share. Internal to bender_io.

#include <nlohmann/json.hpp>

#include <string>

namespace bender
{
namespace plan_format
{

// Ordered: unknown fields are written back with their members in the order they were read.
using json = nlohmann::ordered_json;

constexpr const char* FormatName = "bender-warps";
constexpr int KnownVersion = 1;
// A plan with Prepare for CFD steps: a reader of version 1 refuses it instead of replaying the
// warps alone (an unknown field would be ignored there, and the surface would not be clipped).
constexpr int CfdStepVersion = 2;
constexpr const char* CfdStepsKey = "prepareForCfd";

// "[json.exception.parse_error.101] parse error at line 3, column 7: ..." without the tag, as
// one printable line: nlohmann quotes the bytes it last read ("last read: '...'"), which come
// from the file and may be anything (found by fuzz/fuzz_plan).
std::string ParseErrorText(const std::string& what);

} // namespace plan_format
} // namespace bender

#endif
