#include "CfdMeshing.h"

#include "BenderErrors.h"
#include "CfdCaseFile.h"
#include "CfdDictionaries.h"
#include "CfdMeshGrading.h"
#include "CfdPatches.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <locale>
#include <sstream>

namespace fs = std::filesystem;

namespace bender
{

std::string BlockMeshDict(const std::array<double, 3>& origin,
  double h,
  const std::array<int, 3>& n)
{
  std::array<double, 3> hi{};
  for (std::size_t k = 0; k < 3; ++k)
  {
    hi[k] = origin[k] + h * n[k];
  }
  std::ostringstream s;
  s << CfdFoamHeader("dictionary", "system", "blockMeshDict");
  s << "// The background box: the surface's bounds plus a margin, cubes of " << CfdNumber(h)
    << " m.\nconvertToMeters 1;\n\nvertices\n(\n";
  const double xs[2] = { origin[0], hi[0] };
  const double ys[2] = { origin[1], hi[1] };
  const double zs[2] = { origin[2], hi[2] };
  const int order[8][3] = { { 0, 0, 0 },
    { 1, 0, 0 },
    { 1, 1, 0 },
    { 0, 1, 0 },
    { 0, 0, 1 },
    { 1, 0, 1 },
    { 1, 1, 1 },
    { 0, 1, 1 } };
  for (const auto& o : order)
  {
    s << "    (" << CfdNumber(xs[o[0]]) << " " << CfdNumber(ys[o[1]]) << " " << CfdNumber(zs[o[2]])
      << ")\n";
  }
  s << ");\n\nblocks\n(\n    hex (0 1 2 3 4 5 6 7) (" << n[0] << " " << n[1] << " " << n[2]
    << ") simpleGrading (1 1 1)\n);\n\nedges\n(\n);\n\n"
       "boundary\n(\n    background\n    {\n        type patch;\n        faces\n        (\n"
       "            (0 3 2 1) (4 5 6 7) (0 4 7 3) (1 2 6 5) (0 1 5 4) (3 7 6 2)\n"
       "        );\n    }\n);\n\nmergePatchPairs\n(\n);\n";
  return s.str();
}

std::string SurfaceFeatureExtractDict(const std::string& stl)
{
  return CfdFoamHeader("dictionary", "system", "surfaceFeatureExtractDict") + stl +
    "\n{\n"
    "    extractionMethod    extractFromSurface;\n"
    "    extractFromSurfaceCoeffs\n    {\n"
    "        // Edges between faces meeting at more than 180 - includedAngle degrees: the rims\n"
    "        // where the ends meet the wall.\n"
    "        includedAngle   150;\n    }\n"
    "    subsetFeatures\n    {\n        nonManifoldEdges    no;\n        openEdges   yes;\n    }\n"
    "    writeObj            no;\n"
    "}\n";
}

std::string SnappyHexMeshDict(const std::string& surfaceName,
  const std::vector<CfdPatch>& patches,
  const std::array<double, 3>& inside,
  double cellSize,
  int layers,
  const CfdMeshGrading& grading)
{
  // Each end's level (1, the wall's, unless the grading refines it) and the finest cell
  // anywhere. The rims of the ends (one feature file for all) stay at the wall's level: a
  // refined end's rim is refined with its surface, and a finer rim would refine the faces of a
  // wider end beyond its level (and under-feed a Poiseuille inlet, whose samples are corrected
  // for faces of its level).
  const auto endLevel = [&grading](const std::string& name)
  {
    for (const CfdEndCells& e : grading.ends)
    {
      if (e.name == name)
      {
        return e.level;
      }
    }
    return 1;
  };
  int finest = 1;
  for (const CfdEndCells& e : grading.ends)
  {
    finest = std::max(finest, e.level);
  }
  for (const CfdRefinementRegion& r : grading.regions)
  {
    finest = std::max(finest, r.level);
  }
  std::ostringstream s;
  s << CfdFoamHeader("dictionary", "system", "snappyHexMeshDict");
  s << "castellatedMesh true;\nsnap            true;\naddLayers       "
    << (layers > 0 ? "true" : "false") << ";\n\n";
  s << "geometry\n{\n    " << surfaceName << ".stl\n    {\n        type triSurfaceMesh;\n"
    << "        name " << surfaceName << ";\n        regions\n        {\n";
  for (const auto& p : patches)
  {
    s << "            " << p.name << " { name " << p.name << "; }\n";
  }
  s << "        }\n    }\n";
  for (const CfdRefinementRegion& r : grading.regions)
  {
    s << "    " << r.name << ".stl { type triSurfaceMesh; name " << r.name << "; }\n";
  }
  s << "}\n\n";
  s << "castellatedMeshControls\n{\n"
       "    maxLocalCells       2000000;\n    maxGlobalCells      8000000;\n"
       "    minRefinementCells  0;\n    maxLoadUnbalance    0.10;\n"
       "    nCellsBetweenLevels 3;\n\n"
       "    features\n    (\n        { file \""
    << surfaceName
    << ".eMesh\"; level 1; }\n    );\n\n"
       "    // One level of refinement at the surface: cells of "
    << CfdNumber(cellSize) << " m at the wall; each end at the level that puts "
    << CfdShort(grading.cellsAcross, 2)
    << " cells across it.\n    refinementSurfaces\n    {\n        " << surfaceName
    << "\n        {\n            level (1 1);\n            patchInfo { type wall; }\n"
       "            regions\n            {\n";
  for (const auto& p : patches)
  {
    const int level = IsEndPatch(p.type) ? endLevel(p.name) : 1;
    s << "                " << p.name << " { level (" << level << " " << level
      << "); patchInfo { type " << (IsEndPatch(p.type) ? "patch" : "wall") << "; } }\n";
  }
  s << "            }\n        }\n    }\n\n"
       "    resolveFeatureAngle 30;\n";
  s << "    // The lumen near the wall where it is narrow, at the level that puts the cells\n"
       "    // across it there (within its local radius of those wall triangles).\n"
       "    refinementRegions\n    {\n";
  for (const CfdRefinementRegion& r : grading.regions)
  {
    s << "        " << r.name << " { mode distance; levels ((" << CfdNumber(r.distance) << " "
      << r.level << ")); }\n";
  }
  s << "    }\n\n"
       "    // A point inside the lumen, behind the inlet.\n"
       "    locationInMesh "
    << CfdVector(inside)
    << ";\n    allowFreeStandingZoneFaces true;\n}\n\n"
       "snapControls\n{\n"
       "    nSmoothPatch        3;\n    tolerance           2.0;\n    nSolveIter          100;\n"
       "    nRelaxIter          5;\n    nFeatureSnapIter    10;\n"
       "    implicitFeatureSnap false;\n    explicitFeatureSnap true;\n"
       "    multiRegionFeatureSnap true;\n}\n\n"
       "// Prism layers on the wall, thinner towards it: the outermost is 0.4 of the local cell,\n"
       "// each one 1.2 times the one below it (sizes relative to the cell they grow from; the\n"
       "// three together about one cell, so that a lumen 7 cells across keeps them whole).\n"
       "addLayersControls\n{\n"
       "    relativeSizes       true;\n    layers\n    {\n";
  for (const auto& p : patches)
  {
    if (layers > 0 && !IsEndPatch(p.type))
    {
      s << "        " << p.name << " { nSurfaceLayers " << layers << "; }\n";
    }
  }
  s << "    }\n"
       "    expansionRatio      1.2;\n    finalLayerThickness 0.4;\n    minThickness        0.1;\n"
       "    nGrow               0;\n    featureAngle        60;\n    slipFeatureAngle    30;\n"
       "    nRelaxIter          3;\n    nSmoothSurfaceNormals 1;\n    nSmoothNormals      3;\n"
       "    nSmoothThickness    10;\n    maxFaceThicknessRatio 0.5;\n"
       "    maxThicknessToMedialRatio 0.3;\n    minMedialAxisAngle  90;\n"
       "    nBufferCellsNoExtrude 0;\n    nLayerIter          50;\n}\n\n"
       "// checkMesh's own limits where it has one (skewness 4), so that a mesh snappyHexMesh\n"
       "// accepts passes checkMesh.\n"
       "meshQualityControls\n{\n"
       "    maxNonOrtho         65;\n    maxBoundarySkewness 4;\n    maxInternalSkewness 4;\n"
       "    maxConcave          80;\n    minVol              "
    << CfdNumber(std::pow(0.01 * CfdLevelCellSize(finest, cellSize), 3))
    << ";\n    minTetQuality       1e-15;\n    minArea             -1;\n"
       "    minTwist            0.02;\n    minDeterminant      0.001;\n"
       "    minFaceWeight       0.05;\n    minVolRatio         0.01;\n"
       "    minTriangleTwist    -1;\n    nSmoothScale        4;\n    errorReduction      0.75;\n"
       "    relaxed\n    {\n        maxNonOrtho     75;\n    }\n}\n\n"
       "mergeTolerance 1e-6;\n";
  return s.str();
}

namespace
{

/// The lines of `text`.
std::vector<std::string> Lines(const std::string& text)
{
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
  {
    lines.push_back(line);
  }
  return lines;
}

/// The layers of snappyHexMesh's last layer table ("patch faces layers overall thickness",
/// then a units line and a rule, then "name faces layers thickness-m thickness-%" per patch).
std::vector<CfdPatchLayers> LayerTable(const std::vector<std::string>& lines)
{
  std::size_t table = lines.size();
  for (std::size_t i = 0; i < lines.size(); ++i)
  {
    if (lines[i].rfind("patch", 0) == 0 && lines[i].find("overall thickness") != std::string::npos)
    {
      table = i;
    }
  }
  std::vector<CfdPatchLayers> patches;
  for (std::size_t i = table + 3; i < lines.size(); ++i)
  {
    std::istringstream words(lines[i]);
    words.imbue(std::locale::classic());
    CfdPatchLayers p;
    double metres = 0.0;
    if (!(words >> p.name >> p.faces >> p.layers >> metres >> p.thicknessPercent))
    {
      break;
    }
    patches.push_back(p);
  }
  return patches;
}

} // namespace

CfdMeshReport ReadCfdMeshReport(const std::string& caseDirectory)
{
  const fs::path dir(caseDirectory);
  CfdMeshReport report;
  const std::string check = ReadTextFile(dir / "log.checkMesh");
  for (const std::string& line : Lines(check))
  {
    std::istringstream words(line);
    std::string key;
    if (words >> key && key == "cells:")
    {
      words >> report.cells;
    }
    if (line.rfind("Mesh OK.", 0) == 0)
    {
      report.meshOk = true;
    }
    if (const std::size_t at = line.find("***"); at != std::string::npos)
    {
      report.failedChecks += (report.failedChecks.empty() ? "" : "; ") + line.substr(at + 3);
    }
  }
  if (report.cells <= 0)
  {
    throw InputError((dir / "log.checkMesh").string() + ": no cell count (was the case meshed?)");
  }
  std::ifstream in(dir / kCfdCaseJson);
  const nlohmann::json record = nlohmann::json::parse(in, nullptr, false);
  if (record.is_object() && record.contains("layers") && record["layers"].is_number_integer())
  {
    report.layersRequested = record["layers"].get<int>();
  }
  const std::vector<std::string> snappy = Lines(ReadTextFile(dir / "log.snappyHexMesh"));
  if (report.layersRequested > 0)
  {
    report.layers = LayerTable(snappy);
    for (CfdPatchLayers& p : report.layers)
    {
      p.coveragePercent = 100.0 * p.layers / report.layersRequested;
    }
  }
  // "Extruding 6504 out of 6633 faces (98.06%)." after each layer iteration: the last counts.
  for (const std::string& line : snappy)
  {
    long long extruded = 0, of = 0;
    std::istringstream words(line);
    std::string extruding, out, ofWord;
    if (words >> extruding >> extruded >> out >> ofWord >> of && extruding == "Extruding" &&
      out == "out")
    {
      report.facesExtruded = extruded;
      report.facesToExtrude = of;
    }
  }
  return report;
}

std::string FormatCfdMeshReport(const CfdMeshReport& r)
{
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s << "mesh: " << r.cells << " cells, "
    << (r.meshOk ? "checkMesh: Mesh OK" : "checkMesh failed: " + r.failedChecks) << "\n";
  if (r.layersRequested <= 0)
  {
    s << "  no prism layers (--layers 0)\n";
    return s.str();
  }
  if (r.layers.empty())
  {
    s << "  prism layers: snappyHexMesh reported none (" << r.layersRequested
      << " asked for on the wall)\n";
  }
  for (const CfdPatchLayers& p : r.layers)
  {
    s << "  prism layers on " << p.name << ": " << CfdShort(p.layers) << " of " << r.layersRequested
      << " on average (" << CfdShort(p.coveragePercent) << " % of the layers), "
      << CfdShort(p.thicknessPercent) << " % of the thickness\n";
  }
  if (r.facesToExtrude > 0)
  {
    const double percent = 100.0 * r.facesExtruded / r.facesToExtrude;
    s << "  " << CfdShort(percent) << " % of the wall's faces have layers";
    if (r.facesExtruded < r.facesToExtrude)
    {
      s << "; layers failed on " << (r.facesToExtrude - r.facesExtruded) << " of "
        << r.facesToExtrude << " faces (" << CfdShort(100.0 - percent, 2) << " %)";
    }
    s << "\n";
  }
  return s.str();
}

nlohmann::ordered_json CfdMeshReportJson(const CfdMeshReport& r)
{
  nlohmann::ordered_json layers = nlohmann::ordered_json::array();
  for (const CfdPatchLayers& p : r.layers)
  {
    layers.push_back({ { "patch", p.name },
      { "faces", p.faces },
      { "layersMean", p.layers },
      { "coveragePercent", p.coveragePercent },
      { "thicknessPercent", p.thicknessPercent } });
  }
  return { { "cells", r.cells },
    { "meshOk", r.meshOk },
    { "failedChecks", r.failedChecks },
    { "layersRequested", r.layersRequested },
    { "layers", layers },
    { "wallFacesWithLayersPercent",
      r.facesToExtrude > 0 ? 100.0 * r.facesExtruded / r.facesToExtrude : 0.0 } };
}

} // namespace bender
