#ifndef bender_FlowPictures_h
#define bender_FlowPictures_h

// The pictures of the flow report (issue 23): the two shapes of a comparison side by side,
// coloured by one quantity (pressure or wall shear stress) on one shared colour scale with one
// scalar bar and its unit, seen from one camera (the same viewpoint for both). Rendered off
// screen with VTK on the display DISPLAY names (bender-cli starts a private Xvfb:
// HeadlessDisplay.h; the window has its own).

#include "CfdCaseComparison.h"
#include "RenderToPng.h"

#include <vtkImageData.h>
#include <vtkSmartPointer.h>

#include <array>
#include <string>
#include <vector>

namespace bender
{

/// A quantity the pictures colour by: a point array of CASE/results/surface.vtp.
struct FlowQuantity
{
  std::string key;   ///< file names and JSON: "pressure", "wss"
  std::string array; ///< point data: "Pressure", "WallShearStressMagnitude"
  std::string title; ///< the scalar bar's title with the unit: "Pressure (Pa)"
  std::string scale; ///< how the shared colour scale is chosen, for the caption
};

/// The quantities of the report, in its order: pressure, then wall shear stress.
const std::vector<FlowQuantity>& FlowQuantities();

/// The colour scale both shapes share for `quantity`: pressure from the lowest to the highest
/// value on either surface; wall shear stress from 0 to the higher of the two 99th percentiles
/// (the few points above show in the top colour, so that one peak does not wash out the rest).
std::array<double, 2> SharedRange(const CfdCaseComparison& comparison,
  const FlowQuantity& quantity);

/// Options of RenderFlowPictures.
struct FlowPictureOptions
{
  int width = 1800; ///< pixels of each picture, [200, 8192]
  int height = 1000;
  std::vector<RenderView> views{ RenderView::Iso, RenderView::Front };
};

/// One picture: one quantity from one viewpoint, A on the left, B on the right.
struct FlowPicture
{
  std::string name;    ///< "pressure-iso": the PNG's base name
  std::string title;   ///< "Pressure (Pa), iso view"
  std::string caption; ///< how the colour scale is chosen
  vtkSmartPointer<vtkImageData> image;
};

/// Renders every quantity from every view. Throws EnvironmentError without a display.
std::vector<FlowPicture> RenderFlowPictures(const CfdCaseComparison& comparison,
  const FlowPictureOptions& options = {});

} // namespace bender

#endif
