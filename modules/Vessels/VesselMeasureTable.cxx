#include "VesselMeasureTable.h"

#include <algorithm>
#include <stdexcept>

namespace bender
{
namespace
{

std::vector<VesselMeasure>& Table()
{
  static std::vector<VesselMeasure> table = {
    { "length", "Length", "mm", 2, [](const BranchMeasures& b) { return b.length; }, true, true },
    { "tortuosity", "Tortuosity", "", 4, [](const BranchMeasures& b) { return b.tortuosity; } },
    { "maxCurvature",
      "Max curvature",
      "1/mm",
      4,
      [](const BranchMeasures& b) { return b.maxCurvature; } },
    { "meanCurvature",
      "Mean curvature",
      "1/mm",
      4,
      [](const BranchMeasures& b) { return b.meanCurvature; },
      false },
    { "bendAngle",
      "Bend angle",
      "deg",
      2,
      [](const BranchMeasures& b) { return b.bendAngle; },
      true,
      true },
    { "minRadius",
      "Min radius",
      "mm",
      2,
      [](const BranchMeasures& b) { return b.minRadius; },
      true,
      true },
    { "meanRadius", "Mean radius", "mm", 2, [](const BranchMeasures& b) { return b.meanRadius; } },
    { "maxRadius", "Max radius", "mm", 2, [](const BranchMeasures& b) { return b.maxRadius; } },
    { "minRadiusAbscissa",
      "Narrowest at",
      "mm",
      2,
      [](const BranchMeasures& b) { return b.minRadiusAbscissa; },
      false },
  };
  return table;
}

} // namespace

const std::vector<VesselMeasure>& VesselMeasureTable()
{
  return Table();
}

void RegisterVesselMeasure(VesselMeasure measure)
{
  if (measure.key.empty() || !measure.get)
  {
    throw std::invalid_argument("vessel measure: a measure needs a key and a getter");
  }
  std::vector<VesselMeasure>& table = Table();
  if (std::any_of(
        table.begin(), table.end(), [&](const VesselMeasure& m) { return m.key == measure.key; }))
  {
    throw std::invalid_argument("vessel measure '" + measure.key + "' is already in the table");
  }
  table.push_back(std::move(measure));
}

bool UnregisterVesselMeasure(const std::string& key)
{
  std::vector<VesselMeasure>& table = Table();
  const auto it =
    std::find_if(table.begin(), table.end(), [&](const VesselMeasure& m) { return m.key == key; });
  if (it == table.end())
  {
    return false;
  }
  table.erase(it);
  return true;
}

std::string MeasureTitle(const VesselMeasure& measure)
{
  return measure.unit.empty() ? measure.label : measure.label + " (" + measure.unit + ")";
}

} // namespace bender
