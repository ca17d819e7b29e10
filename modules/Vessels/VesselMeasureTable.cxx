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
    { "length", "Length", "mm", 2, [](const BranchMeasures& b) { return b.Length; }, true, true },
    { "tortuosity", "Tortuosity", "", 4, [](const BranchMeasures& b) { return b.Tortuosity; } },
    { "maxCurvature",
      "Max curvature",
      "1/mm",
      4,
      [](const BranchMeasures& b) { return b.MaxCurvature; } },
    { "meanCurvature",
      "Mean curvature",
      "1/mm",
      4,
      [](const BranchMeasures& b) { return b.MeanCurvature; },
      false },
    { "bendAngle",
      "Bend angle",
      "deg",
      2,
      [](const BranchMeasures& b) { return b.BendAngle; },
      true,
      true },
    { "minRadius",
      "Min radius",
      "mm",
      2,
      [](const BranchMeasures& b) { return b.MinRadius; },
      true,
      true },
    { "meanRadius", "Mean radius", "mm", 2, [](const BranchMeasures& b) { return b.MeanRadius; } },
    { "maxRadius", "Max radius", "mm", 2, [](const BranchMeasures& b) { return b.MaxRadius; } },
    { "minRadiusAbscissa",
      "Narrowest at",
      "mm",
      2,
      [](const BranchMeasures& b) { return b.MinRadiusAbscissa; },
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
  if (measure.Key.empty() || !measure.Get)
  {
    throw std::invalid_argument("vessel measure: a measure needs a key and a getter");
  }
  std::vector<VesselMeasure>& table = Table();
  if (std::any_of(
        table.begin(), table.end(), [&](const VesselMeasure& m) { return m.Key == measure.Key; }))
  {
    throw std::invalid_argument("vessel measure '" + measure.Key + "' is already in the table");
  }
  table.push_back(std::move(measure));
}

bool UnregisterVesselMeasure(const std::string& key)
{
  std::vector<VesselMeasure>& table = Table();
  const auto it =
    std::find_if(table.begin(), table.end(), [&](const VesselMeasure& m) { return m.Key == key; });
  if (it == table.end())
  {
    return false;
  }
  table.erase(it);
  return true;
}

std::string MeasureTitle(const VesselMeasure& measure)
{
  return measure.Unit.empty() ? measure.Label : measure.Label + " (" + measure.Unit + ")";
}

} // namespace bender
