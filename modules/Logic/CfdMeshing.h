#ifndef bender_CfdMeshing_h
#define bender_CfdMeshing_h

// The mesh of an OpenFOAM case written by WriteOpenFoamCase (CfdCase.h): the dictionaries of
// blockMesh (the background box), surfaceFeatureExtract (the rims of the ends) and
// snappyHexMesh (refined at the wall, prism layers on it), and what the meshers reported
// (the layers each patch got, checkMesh's verdict), read back from their logs.

#include "CfdCase.h"

#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <vector>

namespace bender
{

/// The background box from `origin` (m), cubes of h, n cells per axis.
std::string BlockMeshDict(const std::array<double, 3>& origin,
  double h,
  const std::array<int, 3>& n);
/// The feature edges of constant/triSurface/`stl` (the rims of the ends).
std::string SurfaceFeatureExtractDict(const std::string& stl);
/// snappyHexMesh on surface `surfaceName` (one region per patch), refined once at the wall
/// to cellSize (m), each end to its level and the lumen near each of the grading's regions
/// (constant/triSurface/<region>.stl) to theirs (CfdMeshGrading.h), the mesh kept on the side
/// of `inside` (m); `layers` prism layers on the wall patches (0: none), sized relative to the
/// local cell.
std::string SnappyHexMeshDict(const std::string& surfaceName,
  const std::vector<CfdPatch>& patches,
  const std::array<double, 3>& inside,
  double cellSize,
  int layers,
  const CfdMeshGrading& grading = {});

/// Reads the report of the mesh of a case already meshed. Throws InputError naming the log
/// when log.checkMesh is missing or has no cell count.
CfdMeshReport ReadCfdMeshReport(const std::string& caseDirectory);

/// The report as lines of text (the layers per patch and where they failed, checkMesh's
/// verdict) and as JSON (units in the keys).
std::string FormatCfdMeshReport(const CfdMeshReport& report);
nlohmann::ordered_json CfdMeshReportJson(const CfdMeshReport& report);

} // namespace bender

#endif
