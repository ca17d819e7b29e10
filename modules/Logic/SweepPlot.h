#ifndef bender_SweepPlot_h
#define bender_SweepPlot_h

// The charts of a sweep (issue 24): pressure drop, flow split per outlet and low-WSS area
// against the varied value, the original drawn as a dashed line across. summary.png
// (WriteSweepPlot) and the window's sweep view draw the same charts.

#include "Sweep.h"

#include <string>
#include <vector>

class vtkChartMatrix;

namespace bender
{

/// Fills `matrix` (set to 3 x 1 here) with the three charts of `rows`. A `highlight` id names
/// the row drawn as a large point on every chart (the candidate shown; empty: none).
void AddSweepCharts(vtkChartMatrix* matrix,
  const std::vector<SweepRow>& rows,
  const std::string& parameter,
  const std::string& highlight = {});

} // namespace bender

#endif
