#include "FlowPictures.h"

#include "BenderErrors.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>
#include <vtkScalarBarActor.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cstdlib>
#include <limits>

namespace bender
{

const std::vector<FlowQuantity>& FlowQuantities()
{
  static const std::vector<FlowQuantity> quantities{
    { "pressure",
      kPressureArrayName,
      "Pressure (Pa)",
      "one scale for both, from the lowest to the highest value on either" },
    { "wss",
      kWallShearStressMagnitudeArrayName,
      "Wall shear stress (Pa)",
      "one scale for both, from 0 to the higher 99th percentile (above it: red)" },
  };
  return quantities;
}

std::array<double, 2> SharedRange(const CfdCaseComparison& comparison, const FlowQuantity& quantity)
{
  if (quantity.key == "wss")
  {
    const double top = std::max(comparison.a.results.wallShearStress.percentile99Pa,
      comparison.b.results.wallShearStress.percentile99Pa);
    return { 0.0, top > 0.0 ? top : 1.0 };
  }
  std::array<double, 2> range{ std::numeric_limits<double>::max(),
    std::numeric_limits<double>::lowest() };
  for (const ComparedCfdCase* c : { &comparison.a, &comparison.b })
  {
    vtkDataArray* values = c->surface->GetPointData()->GetArray(quantity.array.c_str());
    if (values && values->GetNumberOfTuples() > 0)
    {
      double r[2];
      values->GetRange(r, -1);
      range[0] = std::min(range[0], r[0]);
      range[1] = std::max(range[1], r[1]);
    }
  }
  if (range[0] > range[1])
  {
    return { 0.0, 1.0 };
  }
  if (range[1] - range[0] < 1e-9)
  {
    range[1] = range[0] + 1.0;
  }
  return range;
}

namespace
{
// One shape's half of the picture: the surface coloured by the shared lookup table, and its
// label at the top.
void AddShape(vtkRenderWindow* window,
  vtkCamera* camera,
  const ComparedCfdCase& shape,
  const FlowQuantity& quantity,
  vtkLookupTable* lut,
  const double viewport[4],
  const std::string& label)
{
  vtkNew<vtkRenderer> renderer;
  renderer->SetViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  renderer->SetBackground(1.0, 1.0, 1.0);
  renderer->SetActiveCamera(camera);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(shape.surface);
  normals->SplittingOff();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(normals->GetOutputPort());
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray(quantity.array.c_str());
  mapper->SetLookupTable(lut);
  mapper->UseLookupTableScalarRangeOn();
  mapper->ScalarVisibilityOn();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetSpecular(0.15);
  renderer->AddActor(actor);
  vtkNew<vtkTextActor> text;
  text->SetInput(label.c_str());
  text->GetTextProperty()->SetFontSize(30);
  text->GetTextProperty()->SetColor(0.1, 0.1, 0.1);
  text->GetTextProperty()->BoldOn();
  text->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  text->GetPositionCoordinate()->SetValue(0.04, 0.04);
  renderer->AddViewProp(text);
  window->AddRenderer(renderer);
}

FlowPicture Render(vtkRenderWindow* window,
  const CfdCaseComparison& comparison,
  const FlowQuantity& quantity,
  RenderView view)
{
  const std::array<double, 2> range = SharedRange(comparison, quantity);
  vtkNew<vtkLookupTable> lut;
  lut->SetHueRange(0.667, 0.0); // blue (low) to red (high)
  lut->SetTableRange(range[0], range[1]);
  lut->SetNumberOfTableValues(256);
  lut->Build();

  // One camera for both halves, framed on the box holding both shapes.
  double bounds[6], other[6];
  comparison.a.surface->GetBounds(bounds);
  comparison.b.surface->GetBounds(other);
  for (int i = 0; i < 3; ++i)
  {
    bounds[2 * i] = std::min(bounds[2 * i], other[2 * i]);
    bounds[2 * i + 1] = std::max(bounds[2 * i + 1], other[2 * i + 1]);
  }
  vtkNew<vtkCamera> camera;
  AimCamera(camera, view);

  // The previous picture's renderers make way for this one's.
  while (vtkRenderer* previous = window->GetRenderers()->GetFirstRenderer())
  {
    window->RemoveRenderer(previous);
  }
  const double left[4] = { 0.0, 0.0, 0.43, 1.0 }, right[4] = { 0.43, 0.0, 0.86, 1.0 };
  AddShape(window, camera, comparison.a, quantity, lut, left, "A: " + comparison.a.label);
  AddShape(window, camera, comparison.b, quantity, lut, right, "B: " + comparison.b.label);
  window->GetRenderers()->GetFirstRenderer()->ResetCamera(bounds);
  camera->Zoom(1.2);

  vtkNew<vtkRenderer> barRenderer;
  barRenderer->SetViewport(0.86, 0.0, 1.0, 1.0);
  barRenderer->SetBackground(1.0, 1.0, 1.0);
  vtkNew<vtkScalarBarActor> bar;
  bar->SetLookupTable(lut);
  bar->SetTitle(quantity.title.c_str());
  bar->SetNumberOfLabels(6);
  bar->SetLabelFormat("%.3g");
  bar->SetUnconstrainedFontSize(true);
  bar->GetTitleTextProperty()->SetFontSize(24);
  bar->GetTitleTextProperty()->SetColor(0.1, 0.1, 0.1);
  bar->GetTitleTextProperty()->ItalicOff();
  bar->GetLabelTextProperty()->SetFontSize(22);
  bar->GetLabelTextProperty()->SetColor(0.1, 0.1, 0.1);
  bar->GetLabelTextProperty()->ItalicOff();
  bar->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  bar->GetPositionCoordinate()->SetValue(0.1, 0.08);
  bar->SetWidth(0.8);
  bar->SetHeight(0.84);
  barRenderer->AddViewProp(bar);
  window->AddRenderer(barRenderer);

  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();

  FlowPicture picture;
  picture.name = quantity.key + "-" + RenderViewName(view);
  picture.title = quantity.title + ", " + RenderViewName(view) + " view";
  picture.caption = "Colour scale: " + quantity.scale + ".";
  picture.image = vtkSmartPointer<vtkImageData>::New();
  picture.image->DeepCopy(grab->GetOutput());
  return picture;
}
} // namespace

std::vector<FlowPicture> RenderFlowPictures(const CfdCaseComparison& comparison,
  const FlowPictureOptions& options)
{
  if (options.width < 200 || options.height < 200 || options.width > 8192 || options.height > 8192)
  {
    throw InputError("report: the picture size must be in 200..8192 pixels");
  }
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    throw EnvironmentError("report: no display: DISPLAY is not set (run under xvfb-run -a, or "
                           "through bender-cli, which starts a private Xvfb)");
  }
  // One window for every picture: GLX contexts are not made and dropped once per picture.
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(options.width, options.height);
  window->SetMultiSamples(0);
  std::vector<FlowPicture> pictures;
  for (const FlowQuantity& quantity : FlowQuantities())
  {
    for (const RenderView view : options.views)
    {
      pictures.push_back(Render(window, comparison, quantity, view));
    }
  }
  return pictures;
}

} // namespace bender
