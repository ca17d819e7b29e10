#ifndef bender_RenderToPng_h
#define bender_RenderToPng_h

#include "BenderErrors.h"
#include "WarpPlan.h"

#include <array>
#include <string>
#include <vector>

class vtkCamera;
class vtkImageData;
class vtkPolyData;
class vtkRenderWindow;

namespace bender
{

/// Camera direction. LPS: +x left, +y posterior, +z superior; Front looks from anterior along +y.
enum class RenderView
{
  Iso,
  Front,
  Back,
  Left,
  Right,
  Top,
  Bottom
};

/// "iso", "front", ... -> the view; false for an unknown name.
bool ParseRenderView(const std::string& name, RenderView& view);
/// The view's name ("iso", "front", ...), as ParseRenderView reads it.
std::string RenderViewName(RenderView view);

/// Points `camera` from the direction of `view` at the origin with its view-up (superior, or
/// anterior for Top and Bottom); the caller then frames it (vtkRenderer::ResetCamera).
void AimCamera(vtkCamera* camera, RenderView view);

/// Writes `image` as a PNG at `path` through the atomic write. Throws InputError naming the
/// path when it cannot be written (nothing is left behind).
void WritePng(vtkImageData* image, const std::string& path);

/// A ribbon drawn as a strip over the surface.
struct RenderRibbon
{
  RibbonSpec ribbon;
  double width = 1.0; ///< model units
  std::array<double, 3> color{ { 0.95, 0.5, 0.1 } };
};

/// Options of RenderToPng.
struct RenderToPngOptions
{
  std::string output; ///< the PNG, written atomically
  int width = 800;    ///< pixels, [16, 8192]
  int height = 600;
  RenderView view = RenderView::Iso;
  bool wireframe = false; ///< draw the triangle edges
  /// Surface colour and opacity (see the ribbons through a translucent surface).
  std::array<double, 3> color{ { 0.85, 0.78, 0.70 } };
  double opacity = 1.0;
  /// White background (documentation figures) or the application's dark gradient.
  bool darkBackground = false;
  /// A second surface drawn as a pale ghost (the surface before the plan); may be null.
  vtkPolyData* ghost = nullptr;
  std::vector<RenderRibbon> ribbons;
};

/// Renders `surface` off screen and writes a PNG (bender-cli render, the headless demo).
/// Debian's VTK renders through an X server: it renders off screen on the display DISPLAY
/// names (the application starts a private Xvfb where there is none: app/cli's
/// HeadlessDisplay). Throws EnvironmentError (one line: DISPLAY is not set), InputError (no
/// surface, bad size, the PNG cannot be written). Nothing is left behind on failure.
void RenderToPng(vtkPolyData* surface, const RenderToPngOptions& options);

/// Renders `window` (off screen, on the display DISPLAY names) and writes its image as a PNG
/// at `path`, atomically. Throws InputError naming the path when it cannot be written.
void WriteRenderWindowPng(vtkRenderWindow* window, const std::string& path);

} // namespace bender

#endif
