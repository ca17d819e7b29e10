#ifndef bender_VesselMeasureTable_h
#define bender_VesselMeasureTable_h

// The one table of the per-branch vessel measures (name, unit, getter). Every list a user sees
// iterates it: the JSON of `bender-cli centerline --json` and `bender-cli measure --json`
// (each branch's measures and their change), the text tables of `bender-cli measure`, and the
// GUI's Measure panel (the held branch and the plan's before/after table). A new measure is one
// row in VesselMeasureTable.cxx, its getter (usually a field of BranchMeasures computed by
// MeasureStretch, VesselMeasures.h) and its test; no caller changes.
// Units: lengths in the centerlines' unit (mm), angles in degrees, curvature in 1/mm.

#include "VesselMeasures.h"

#include <functional>
#include <string>
#include <vector>

namespace bender
{

struct VesselMeasure
{
  std::string key;   ///< JSON key, camelCase ("bendAngle"); unique in the table
  std::string label; ///< title in the text tables and the panel ("Bend angle")
  std::string unit;  ///< "mm", "deg", "1/mm"; empty for a ratio
  int decimals = 2;  ///< digits after the point in the text tables and the panel (JSON: 4)
  std::function<double(const BranchMeasures&)> get;
  bool text = true;   ///< a column of the text tables
  bool panel = false; ///< a row of the panel's held-branch table and a column of its plan table
};

/// The measures, in the order the JSON, the text tables and the panel list them.
const std::vector<VesselMeasure>& VesselMeasureTable();

/// Appends a row (an extension, a test). Throws std::invalid_argument for an empty key, a key
/// already in the table or no getter.
void RegisterVesselMeasure(VesselMeasure measure);

/// Removes the row with `key`; false when there is none.
bool UnregisterVesselMeasure(const std::string& key);

/// The label with its unit, "Bend angle (deg)"; the label alone without a unit.
std::string MeasureTitle(const VesselMeasure& measure);

} // namespace bender

#endif
