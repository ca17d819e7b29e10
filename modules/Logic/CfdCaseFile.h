#ifndef bender_CfdCaseFile_h
#define bender_CfdCaseFile_h

// bender-case.json, the record of a case that the runner and the result reader read back.

#include "CfdCase.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace bender
{

/// The record's name in the case folder.
inline constexpr const char* kCfdCaseJson = "bender-case.json";

/// The patches as the record and CfdToJson list them.
nlohmann::ordered_json CfdPatchesJson(const std::vector<CfdPatch>& patches);

/// The empty file in the case folder that names the case for vtkOpenFOAMReader (ParaView's
/// convention), written when missing; its path. Throws Error when it cannot be written.
std::string CfdFoamFile(const std::filesystem::path& caseDirectory);

/// The whole text of `path`; empty when it cannot be read (a log not written yet).
std::string ReadTextFile(const std::filesystem::path& path);

} // namespace bender

#endif
