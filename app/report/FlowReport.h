#ifndef bender_FlowReport_h
#define bender_FlowReport_h

// The flow report (issue 23, "a report a surgeon brings to the planning meeting"): one PDF,
// written with Qt's QPdfWriter, of a comparison of two CFD cases (CompareCfdCases): the
// cases and the provenance (software version, date), the plan's description and warps, each
// branch's bend measures, the comparison table with its highlighted rows and the rule, the
// pictures of both shapes coloured by pressure and by wall shear stress (FlowPictures.h), and
// the mesh and convergence figures of each case. A PNG of each picture beside it on request.
// Shared by bender-cli compare and the application; needs a QGuiApplication, which it creates
// (on Qt's offscreen platform) when the process has none.

#include "CfdCaseComparison.h"
#include "FlowPictures.h"

#include <string>
#include <vector>

namespace bender
{

/// Options of WriteFlowReport.
struct FlowReportOptions
{
  std::string output;    ///< the PDF, written atomically (nothing at the path on failure)
  std::string pngFolder; ///< empty: no PNGs; else one PNG per picture (created if missing)
  std::string version;   ///< empty: this build's (BENDER_VERSION)
  std::string date;      ///< empty: now, UTC ("2026-11-27 02:10 UTC")
  FlowPictureOptions pictures;
};

/// What WriteFlowReport wrote.
struct FlowReportResult
{
  std::string pdf;
  int pages = 0;
  std::vector<std::string> pngs;
};

/// This build's version ("0.1.0").
std::string BenderVersion();

/// Renders the pictures and writes the report. Throws InputError naming the output (cannot be
/// written, the PNG folder cannot be made), EnvironmentError without a display.
FlowReportResult WriteFlowReport(const CfdCaseComparison& comparison,
  const FlowReportOptions& options);

} // namespace bender

#endif
