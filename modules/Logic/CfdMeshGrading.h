#ifndef bender_CfdMeshGrading_h
#define bender_CfdMeshGrading_h

// Cells where they are needed (issue 23): the refinement of a case's mesh graded by the local
// width of the lumen instead of one cell size set by the smallest end. The lumen's local
// diameter is measured at every wall triangle (the chord along its inward normal to the opposite
// wall, smoothed by medians over its neighbours) and at every end (its equivalent diameter).
// The wall's base cell is the case's cell size H (level 1 of snappyHexMesh, the background being
// 2H); each end, and the lumen near each narrower stretch of wall, is refined by levels (each
// halves the cell) until it has the cells across that the case asks for.

#include "CfdCase.h"
#include "LabelledSurface.h"

#include <nlohmann/json.hpp>
#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

/// The wall cells across every end when neither the cell size nor the count is given; the
/// default cell size is then the largest end's diameter over it.
constexpr double kCfdDefaultCellsAcross = 8.0;
/// The share of the cells across that a stretch of wall may lack before it is refined: the
/// local diameter measured on a segmented wall scatters by about a voxel, and without this
/// margin a branch as wide as a level's threshold would be refined patch by patch.
constexpr double kCfdWallCellsMargin = 0.9;
/// The levels above the base that a narrow place may get (each halves the cell: H / 8).
constexpr int kCfdMaxExtraLevels = 3;

/// The grading and the surface of each refinement region (LPS millimetres, the region's wall
/// triangles), in the order of grading.regions.
struct CfdGradedMesh
{
  CfdMeshGrading grading;
  std::vector<vtkSmartPointer<vtkPolyData>> regionSurfaces;
};

/// The lumen's local diameter at each cell of `surface` (its unit) where `measure` is true: the
/// distance from the cell's centre along its inward normal to the surface beyond, then the
/// median over the cell and its neighbours (sharing a point), three times; 0 where not measured
/// or where the chord finds no wall (a degenerate triangle). `surface` is closed and consistently
/// oriented, either way round.
std::vector<double> LocalLumenDiameters(vtkPolyData* surface, const std::vector<bool>& measure);

/// The refinement level (1: the base, cells of cellSize; each level above halves the cell, up to
/// 1 + kCfdMaxExtraLevels) that gives at least `cellsAcross` cells across `diameter` (same unit
/// as cellSize).
int CfdRefinementLevel(double diameter, double cellSize, double cellsAcross);

/// The cell size of `level` for a case of base cell size `cellSize`.
double CfdLevelCellSize(int level, double cellSize);

/// Grades the mesh of `surface` (LPS mm; its patches measured as `patches`, metres) of base cell
/// size `cellSize` (m): each end's level from its diameter (at least cellsAcross within 1 %),
/// the wall's from LocalLumenDiameters
/// (at least kCfdWallCellsMargin x cellsAcross); one region per level above the base, named
/// refinement_level_N, holding the wall triangles of that level or finer, refined within their
/// largest local radius. The levels depend on cellSize x cellsAcross only.
CfdGradedMesh GradeCfdMesh(const LabelledSurface& surface,
  const std::vector<CfdPatch>& patches,
  double cellSize,
  double cellsAcross);

/// The grading as lines of the case report: the cells across each end, the fewest across the
/// lumen on the wall and where it is narrowest, and each refinement region.
std::string FormatCfdMeshGrading(const CfdMeshGrading& grading);
/// The grading as JSON (units in the keys).
nlohmann::ordered_json CfdMeshGradingJson(const CfdMeshGrading& grading);

} // namespace bender

#endif
