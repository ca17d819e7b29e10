#ifndef bender_CfdComparison_h
#define bender_CfdComparison_h

// The comparison of two CFD results of the same vessel (issue 23: the original and a bent
// candidate), as one table that bender-cli compare prints, the report shows and the Flow panel
// fills: the pressure drop and the flow split of every outlet (matched by name; an outlet of
// one case only is listed with the other value missing), the wall shear stress statistics,
// the low- and high-WSS areas, the mesh and the run's convergence.
//
// Every row holds A's and B's value, the difference B - A and the relative difference
// (B - A) / |A|. A row is highlighted when the difference is notable (CfdHighlightRule).

#include <optional>
#include <string>
#include <vector>

namespace bender
{
struct CfdFlowResults;

/// When a difference is highlighted: a flow row whose relative difference |B - A| / |A| is
/// above `relative` (5 %) and whose absolute difference is above the row's floor (so that a
/// value near zero, 0.02 -> 0.03 Pa, is not "50 % higher"); with A = 0, the floor alone
/// decides. An outlet of one case only and a run that did not converge are always highlighted.
/// Rows that describe the shapes, not the flow (mesh cells, the wall area), are never
/// highlighted: two shapes have different meshes and walls by design.
struct CfdHighlightRule
{
  double relative = 0.05;
  double pressureFloor = 1.0; ///< Pa
  double splitFloor = 1.0;    ///< percentage points of the inlet flow
  double flowRateFloor = 1.0; ///< ml/min
  double stressFloor = 0.05;  ///< Pa
  double areaFloor = 1.0;     ///< mm^2
};

/// What a row compares (its floor and whether it can be highlighted follow from it).
enum class CfdRowKind
{
  Pressure,
  Split,
  FlowRate,
  Stress,
  Area,
  Geometry, ///< the wall area: shown, never highlighted
  Mesh,
  Run
};

/// One row of the comparison.
struct CfdComparisonRow
{
  std::string key;   ///< stable JSON key: "pressureDrop.outlet_1", "wss.mean", "mesh.cells"
  std::string label; ///< for people: "Pressure drop to outlet_1"
  std::string unit;  ///< "Pa", "%", "ml/min", "mm^2", "" (counts, states)
  CfdRowKind kind = CfdRowKind::Pressure;
  std::optional<double> a; ///< missing: the quantity does not exist in case A (an outlet)
  std::optional<double> b;
  /// Values that are states, not numbers ("converged", "stopped at 500 iterations"); the
  /// numbers a, b then hold what can be compared (iterations).
  std::string textA, textB;
  std::optional<double> difference; ///< b - a, when both exist
  std::optional<double> relative;   ///< (b - a) / |a|, when both exist and a != 0
  bool highlighted = false;
  std::string note; ///< why highlighted or what is missing ("only in B"); may be empty
};

/// The comparison of case A (the reference, the original vessel) with case B.
struct CfdComparison
{
  std::string labelA = "A"; ///< what A and B are called in the table ("original")
  std::string labelB = "B";
  CfdHighlightRule rule;
  std::vector<CfdComparisonRow> rows;
  /// Things to say beside the table: the inlets differ, the inlet flows differ by N %.
  std::vector<std::string> notes;
};

/// Fills the difference, the relative difference and the highlight of `row` by `rule`.
void CompareCfdRow(CfdComparisonRow& row, const CfdHighlightRule& rule);

/// The comparison table of two results: outlets in A's order, then those of B only; then the
/// WSS statistics, the areas, the mesh and the run. Never throws for well-formed results.
CfdComparison CompareCfdResults(const CfdFlowResults& a,
  const CfdFlowResults& b,
  const CfdHighlightRule& rule = {});

/// The number of highlighted rows.
int CountHighlighted(const CfdComparison& comparison);

/// The table as aligned text for a terminal: one row a line (label, A, B, difference, relative
/// difference, a "*" on highlighted rows), then the notes and the rule.
std::string CfdComparisonToText(const CfdComparison& comparison);

/// The table as one JSON object ("format": "bender-flow-comparison", "version": 1, "caseA",
/// "caseB", "rule", "rows": [{"key", "label", "unit", "a", "b", "difference",
/// "relativeDifference", "highlighted", "note"}], "notes"); missing values are null.
std::string CfdComparisonToJson(const CfdComparison& comparison, int indent = 2);

/// The rule in one sentence, for the report and the help.
std::string DescribeHighlightRule(const CfdHighlightRule& rule);

/// A number with `decimals` decimals (no trailing zeros trimmed; "-" for a missing value).
std::string FormatCfdValue(const std::optional<double>& value, int decimals);
/// The decimals a row's values are shown with (Pa 1, % 1, ml/min 1, mm^2 1, Pa of WSS 2).
int CfdRowDecimals(const CfdComparisonRow& row);

} // namespace bender

#endif
