#include "BenderView.h"

#include "BenderSession.h"
#include "MainActions.h"

#include "vtkBenderRibbonRepresentation.h"
#include "vtkBenderRibbonWidget.h"

#include <QAction>

#include <vtkActor.h>
#include <vtkActor2D.h>
#include <vtkAlgorithmOutput.h>
#include <vtkAnnotatedCubeActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellPicker.h>
#include <vtkCommand.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkMath.h>
#include <vtkOrientationMarkerWidget.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataMapper2D.h>
#include <vtkProperty.h>
#include <vtkProperty2D.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace
{
bool ValidBounds(const double b[6])
{
  return b[0] <= b[1] && b[2] <= b[3] && b[4] <= b[5] && std::isfinite(b[0]) &&
    std::isfinite(b[1]) && std::isfinite(b[2]) && std::isfinite(b[3]) && std::isfinite(b[4]) &&
    std::isfinite(b[5]);
}

double Diagonal(const double b[6])
{
  return std::sqrt(
    (b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
}

// The largest of 1, 2, 5 x 10^k not above `value` (> 0).
double NiceLength(double value)
{
  const double decade = std::pow(10.0, std::floor(std::log10(value)));
  for (double step : { 5.0, 2.0, 1.0 })
  {
    if (step * decade <= value)
    {
      return step * decade;
    }
  }
  return decade;
}
}

BenderView::BenderView(vtkAlgorithmOutput* surface, QWidget* parent)
  : QVTKOpenGLNativeWidget(parent)
{
  this->setObjectName("view3d");
  this->setRenderWindow(this->Window);
  this->Window->AddRenderer(this->Renderer);
  this->Renderer->SetBackground(0.12, 0.13, 0.16);
  this->Renderer->SetBackground2(0.32, 0.34, 0.40);
  this->Renderer->GradientBackgroundOn();
  // The ribbon in a layer above the surface, with the same camera and its own depth buffer:
  // its handles and strip stay visible through the vessel. Not interactive: the camera style
  // works on the surface's renderer (the widget is given its renderer explicitly).
  this->Window->SetNumberOfLayers(2);
  this->RibbonRenderer->SetLayer(1);
  this->RibbonRenderer->InteractiveOff();
  this->RibbonRenderer->SetActiveCamera(this->Renderer->GetActiveCamera());
  this->Window->AddRenderer(this->RibbonRenderer);
  // Multisampling with blended translucency draws stripes on software OpenGL (llvmpipe).
  this->Window->SetMultiSamples(0);
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  this->Window->GetInteractor()->SetInteractorStyle(style);

  // Connected once: every change of the session's pipeline reaches the mapper by itself.
  this->SurfaceMapper->SetInputConnection(surface);
  this->SurfaceMapper->ScalarVisibilityOff();
  this->SurfaceActor->SetMapper(this->SurfaceMapper);
  this->SurfaceActor->GetProperty()->SetColor(0.86, 0.36, 0.32);
  this->SurfaceActor->GetProperty()->SetSpecular(0.3);
  this->SurfaceActor->GetProperty()->SetSpecularPower(20);
  this->Renderer->AddActor(this->SurfaceActor);
  // The decimated copy drawn while the camera moves or a big surface is dragged (same look).
  this->ProxyMapper->ScalarVisibilityOff();
  this->ProxyActor->SetMapper(this->ProxyMapper);
  this->ProxyActor->SetProperty(this->SurfaceActor->GetProperty());
  this->ProxyActor->PickableOff();
  this->ProxyActor->VisibilityOff();
  this->Renderer->AddActor(this->ProxyActor);
  // The original shape: pale, faint, pushed behind where it coincides with the surface.
  this->GhostMapper->ScalarVisibilityOff();
  this->GhostMapper->SetResolveCoincidentTopologyToPolygonOffset();
  this->GhostMapper->SetRelativeCoincidentTopologyPolygonOffsetParameters(2.0, 4.0);
  this->GhostActor->SetMapper(this->GhostMapper);
  this->GhostActor->GetProperty()->SetColor(0.85, 0.88, 0.95);
  this->GhostActor->GetProperty()->SetOpacity(0.25);
  this->GhostActor->GetProperty()->BackfaceCullingOn();
  this->GhostActor->PickableOff();
  this->GhostActor->VisibilityOff();
  // Blended in the opaque pass, after the surface and its copy (added after them, so that what
  // lies behind the ghost is drawn before it is blended): a translucent prop would
  // make every frame go through the order-independent translucency passes, full-screen work
  // that costs software OpenGL more than drawing the demo vessel itself.
  this->GhostActor->ForceOpaqueOn();
  this->Renderer->AddActor(this->GhostActor);
  // The centerlines: thick lines drawn as tubes, light so that they read through the wall.
  this->CenterlineMapper->ScalarVisibilityOff();
  this->CenterlineActor->SetMapper(this->CenterlineMapper);
  this->CenterlineActor->GetProperty()->SetColor(0.98, 0.92, 0.45);
  this->CenterlineActor->GetProperty()->SetLineWidth(4.0);
  this->CenterlineActor->GetProperty()->SetRenderLinesAsTubes(true);
  this->CenterlineActor->PickableOff();
  this->CenterlineActor->VisibilityOff();
  this->Renderer->AddActor(this->CenterlineActor);

  // The scale bar: a bar with end ticks, bottom right, its length in mm above it.
  vtkNew<vtkPolyData> bar;
  this->ScaleMapper->SetInputData(bar);
  this->ScaleBar->SetMapper(this->ScaleMapper);
  this->ScaleBar->GetProperty()->SetColor(0.95, 0.95, 0.95);
  this->ScaleBar->GetProperty()->SetLineWidth(2.0);
  this->ScaleBar->PickableOff();
  this->Renderer->AddViewProp(this->ScaleBar);
  this->ScaleText->GetTextProperty()->SetFontSize(14);
  this->ScaleText->GetTextProperty()->SetColor(0.95, 0.95, 0.95);
  this->ScaleText->GetTextProperty()->SetJustificationToCentered();
  this->ScaleText->GetTextProperty()->ShadowOn();
  this->ScaleText->PickableOff();
  this->Renderer->AddViewProp(this->ScaleText);

  this->RibbonWidget->SetInteractor(this->Window->GetInteractor());
  this->RibbonWidget->SetDefaultRenderer(this->RibbonRenderer);
  this->RibbonWidget->SetCurrentRenderer(this->RibbonRenderer);
  this->RibbonWidget->CreateDefaultRepresentation();
  this->RibbonObserver->SetCallback(&BenderView::RibbonCallback);
  this->RibbonObserver->SetClientData(this);
  this->RibbonWidget->AddObserver(vtkCommand::InteractionEvent, this->RibbonObserver);
  this->RibbonWidget->AddObserver(vtkCommand::EndInteractionEvent, this->RibbonObserver);
  this->PickObserver->SetCallback(&BenderView::PickCallback);
  this->PickObserver->SetClientData(this);
  this->Window->GetInteractor()->AddObserver(
    vtkCommand::LeftButtonPressEvent, this->PickObserver, 10.0f);
  this->StartRenderObserver->SetCallback(&BenderView::StartRenderCallback);
  this->StartRenderObserver->SetClientData(this);
  this->Renderer->AddObserver(vtkCommand::StartEvent, this->StartRenderObserver);
  this->CameraObserver->SetCallback(&BenderView::CameraInteractionCallback);
  this->CameraObserver->SetClientData(this);
  style->AddObserver(vtkCommand::StartInteractionEvent, this->CameraObserver);
  style->AddObserver(vtkCommand::EndInteractionEvent, this->CameraObserver);

  // The orientation marker: a cube labelled with the patient directions of the LPS frame.
  this->MarkerCube->SetXPlusFaceText("L");
  this->MarkerCube->SetXMinusFaceText("R");
  this->MarkerCube->SetYPlusFaceText("P");
  this->MarkerCube->SetYMinusFaceText("A");
  this->MarkerCube->SetZPlusFaceText("S");
  this->MarkerCube->SetZMinusFaceText("I");
  this->MarkerCube->SetXFaceTextRotation(0);
  this->MarkerCube->SetYFaceTextRotation(0);
  this->MarkerCube->SetZFaceTextRotation(90);
  this->MarkerCube->SetFaceTextScale(0.62);
  this->MarkerCube->GetCubeProperty()->SetColor(0.32, 0.36, 0.44);
  this->MarkerCube->GetTextEdgesProperty()->SetColor(0.9, 0.9, 0.9);
  this->MarkerCube->GetTextEdgesProperty()->SetLineWidth(1.0);
  this->MarkerCube->GetXPlusFaceProperty()->SetColor(1.0, 0.45, 0.45);
  this->MarkerCube->GetXMinusFaceProperty()->SetColor(1.0, 0.45, 0.45);
  this->MarkerCube->GetYPlusFaceProperty()->SetColor(0.5, 1.0, 0.5);
  this->MarkerCube->GetYMinusFaceProperty()->SetColor(0.5, 1.0, 0.5);
  this->MarkerCube->GetZPlusFaceProperty()->SetColor(0.55, 0.7, 1.0);
  this->MarkerCube->GetZMinusFaceProperty()->SetColor(0.55, 0.7, 1.0);
  this->Marker->SetOrientationMarker(this->MarkerCube);
  this->Marker->SetInteractor(this->Window->GetInteractor());
  this->Marker->SetDefaultRenderer(this->Renderer);
  this->Marker->SetViewport(0.0, 0.0, 0.13, 0.17);
  this->Marker->SetEnabled(1);
  this->Marker->InteractiveOff();

  this->setStandardView(Anterior);
}

BenderView::~BenderView()
{
  this->RibbonWidget->Off();
  this->Marker->SetEnabled(0);
}

void BenderView::setCenterlines(vtkPolyData* lines)
{
  if (lines)
  {
    this->CenterlineMapper->SetInputData(lines);
  }
  else
  {
    this->CenterlineMapper->RemoveAllInputs();
  }
  this->CenterlineActor->SetVisibility(lines != nullptr);
  this->setCenterlinesVisible(this->CenterlinesVisible);
}

void BenderView::moveCenterlines(vtkPolyData* lines)
{
  if (lines && this->CenterlineMapper->GetNumberOfInputConnections(0) > 0)
  {
    this->CenterlineMapper->SetInputData(lines);
  }
}

void BenderView::setCenterlinesVisible(bool visible)
{
  this->CenterlinesVisible = visible;
  const bool shown = visible && this->CenterlineMapper->GetNumberOfInputConnections(0) > 0;
  this->CenterlineActor->SetVisibility(shown);
  // Translucent enough to see the line inside, opaque enough to keep the shape readable.
  this->SurfaceActor->GetProperty()->SetOpacity(shown ? 0.45 : 1.0);
  // Behind a translucent surface the ghost must be sorted with it (translucent pass).
  this->GhostActor->SetForceOpaque(!shown);
  this->render();
}

bool BenderView::centerlinesShown() const
{
  return this->CenterlineActor->GetVisibility() != 0;
}

void BenderView::setOriginalSurface(vtkPolyData* original, bool differs)
{
  if (original != this->GhostOriginal ||
    (original && original->GetMTime() != this->GhostOriginalTime))
  {
    this->GhostOriginal = original;
    this->GhostOriginalTime = original ? original->GetMTime() : 0;
    this->GhostCopy = nullptr;
    if (!original)
    {
      this->GhostMapper->RemoveAllInputs();
    }
  }
  this->GhostDiffers = differs;
  this->updateGhostInput();
}

void BenderView::setOriginalInPlay(std::function<vtkPolyData*()> inPlay)
{
  this->GhostInPlay = std::move(inPlay);
  this->updateGhostInput();
}

void BenderView::setOriginalVisible(bool visible)
{
  this->GhostWanted = visible;
  this->updateGhostInput();
  this->render();
}

void BenderView::updateGhostInput()
{
  const bool shown = this->GhostOriginal && this->GhostDiffers && this->GhostWanted;
  if (shown)
  {
    vtkPolyData* drawn = this->GhostOriginal;
    if (this->GhostOriginal->GetNumberOfPolys() > this->LodThreshold)
    {
      // A faint ghost needs no detail: a big original is drawn as its decimated copy, made
      // once, when it is first shown.
      if (!this->GhostCopy)
      {
        this->GhostCopy = bender::MakeLevelOfDetail(this->GhostOriginal);
      }
      drawn = this->GhostCopy;
    }
    else if (this->GhostInPlay)
    {
      if (vtkPolyData* inPlay = this->GhostInPlay())
      {
        drawn = inPlay;
      }
    }
    if (this->GhostMapper->GetInput() != drawn)
    {
      this->GhostMapper->SetInputData(drawn);
    }
  }
  this->GhostActor->SetVisibility(shown);
}

bool BenderView::originalShown() const
{
  return this->GhostActor->GetVisibility() != 0;
}

void BenderView::render()
{
  if (this->Quiet == 0)
  {
    this->Window->Render();
  }
}

void BenderView::quietly(const std::function<void()>& call)
{
  ++this->Quiet;
  try
  {
    call();
  }
  catch (...)
  {
    --this->Quiet;
    throw;
  }
  --this->Quiet;
}

bool BenderView::sceneBounds(double bounds[6])
{
  // The surface alone (not the ribbon, the marker or an old scene's leftovers).
  this->SurfaceMapper->Update();
  vtkPolyData* surface = vtkPolyData::SafeDownCast(this->SurfaceMapper->GetInput());
  if (!surface || surface->GetNumberOfPoints() == 0)
  {
    return false;
  }
  surface->GetBounds(bounds);
  return ValidBounds(bounds);
}

void BenderView::attachActions(MainActions* actions)
{
  connect(actions->ResetCamera, &QAction::triggered, this, &BenderView::resetCamera);
  for (int v = 0; v < 6; ++v)
  {
    connect(actions->StandardViews[v],
      &QAction::triggered,
      this,
      [this, v]() { this->setStandardView(static_cast<StandardView>(v)); });
  }
  connect(actions->ShowOriginal, &QAction::toggled, this, &BenderView::setOriginalVisible);
}

void BenderView::resetCamera()
{
  this->setStandardView(Anterior);
}

void BenderView::setStandardView(StandardView view)
{
  // Direction from the focal point to the camera, and the view-up, in LPS.
  static const double toCamera[6][3] = {
    { 0, -1, 0 }, { 0, 1, 0 }, { 1, 0, 0 }, { -1, 0, 0 }, { 0, 0, 1 }, { 0, 0, -1 }
  };
  static const double up[6][3] = {
    { 0, 0, 1 }, { 0, 0, 1 }, { 0, 0, 1 }, { 0, 0, 1 }, { 0, -1, 0 }, { 0, -1, 0 }
  };
  const int v = std::max(0, std::min(5, static_cast<int>(view)));
  double bounds[6] = { -1, 1, -1, 1, -1, 1 };
  const bool hasScene = this->sceneBounds(bounds);
  const double centre[3] = {
    0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5])
  };
  vtkCamera* camera = this->Renderer->GetActiveCamera();
  camera->SetFocalPoint(centre);
  camera->SetPosition(
    centre[0] + toCamera[v][0], centre[1] + toCamera[v][1], centre[2] + toCamera[v][2]);
  camera->SetViewUp(up[v][0], up[v][1], up[v][2]);
  this->Renderer->ResetCamera(bounds);
  if (hasScene)
  {
    std::copy(bounds, bounds + 6, this->FramedBounds);
  }
  this->render();
}

bool BenderView::frameIfNewScene()
{
  double bounds[6];
  if (!this->sceneBounds(bounds))
  {
    return false;
  }
  bool reset = !ValidBounds(this->FramedBounds);
  if (!reset)
  {
    // Another size (4 times larger or smaller), or moved by more than the larger of the two.
    const double before = std::max(Diagonal(this->FramedBounds), 1e-12);
    const double now = std::max(Diagonal(bounds), 1e-12);
    double shift = 0.0;
    for (int i = 0; i < 3; ++i)
    {
      const double d = 0.5 * (bounds[2 * i] + bounds[2 * i + 1]) -
        0.5 * (this->FramedBounds[2 * i] + this->FramedBounds[2 * i + 1]);
      shift += d * d;
    }
    reset = now > 4.0 * before || now < 0.25 * before || std::sqrt(shift) > std::max(before, now);
  }
  if (reset)
  {
    // A ribbon left from the previous scene, outside this surface, is put away: it would
    // bend nothing (and grabbing it would warp empty space). Placing a ribbon shows it again.
    auto* rep = this->RibbonWidget->GetRibbonRepresentation();
    const double margin = 0.1 * Diagonal(bounds);
    auto inside = [&](const bender::Vec3& p)
    {
      return p.x >= bounds[0] - margin && p.x <= bounds[1] + margin && p.y >= bounds[2] - margin &&
        p.y <= bounds[3] + margin && p.z >= bounds[4] - margin && p.z <= bounds[5] + margin;
    };
    if (this->RibbonWidget->GetEnabled() &&
      !(inside(rep->GetRibbon().start.position) && inside(rep->GetRibbon().end.position)))
    {
      this->RibbonWidget->Off();
    }
    this->resetCamera();
  }
  return reset;
}

void BenderView::StartRenderCallback(vtkObject*, unsigned long, void* clientData, void*)
{
  static_cast<BenderView*>(clientData)->beforeFrame();
}

void BenderView::beforeFrame()
{
  // First which surface is drawn (the bounds below are the drawn props').
  this->chooseLevelOfDetail();
  // The style resets the clipping range to the surface's renderer only: widen it to the
  // ribbon's layer, which shares the camera.
  double bounds[6], ribbon[6];
  this->Renderer->ComputeVisiblePropBounds(bounds);
  this->RibbonRenderer->ComputeVisiblePropBounds(ribbon);
  if (ValidBounds(ribbon))
  {
    for (int i = 0; i < 3; ++i)
    {
      bounds[2 * i] = ValidBounds(bounds) ? std::min(bounds[2 * i], ribbon[2 * i]) : ribbon[2 * i];
      bounds[2 * i + 1] =
        ValidBounds(bounds) ? std::max(bounds[2 * i + 1], ribbon[2 * i + 1]) : ribbon[2 * i + 1];
    }
  }
  if (ValidBounds(bounds))
  {
    this->Renderer->ResetCameraClippingRange(bounds);
  }
  this->updateScaleBar();
}

void BenderView::updateScaleBar()
{
  const int* size = this->Renderer->GetSize();
  vtkCamera* camera = this->Renderer->GetActiveCamera();
  // The height of the view at the focal point, in model units (mm).
  const double height = camera->GetParallelProjection() ? 2.0 * camera->GetParallelScale()
                                                        : 2.0 * camera->GetDistance() *
      std::tan(vtkMath::RadiansFromDegrees(0.5 * camera->GetViewAngle()));
  const bool shown = size[0] > 120 && size[1] > 60 && std::isfinite(height) && height > 0.0;
  this->ScaleBar->SetVisibility(shown);
  this->ScaleText->SetVisibility(shown);
  if (!shown)
  {
    return;
  }
  const double pixelsPerMm = size[1] / height;
  const double millimetres = NiceLength(std::min(0.2 * size[0], 140.0) / pixelsPerMm);
  const double pixels = millimetres * pixelsPerMm;
  if (millimetres == this->ScaleMillimetres && pixels == this->ScalePixels)
  {
    return;
  }
  this->ScaleMillimetres = millimetres;
  this->ScalePixels = pixels;
  const double x1 = size[0] - 24.0, x0 = x1 - pixels, y = 22.0, tick = 6.0;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(x0, y + tick, 0);
  points->InsertNextPoint(x0, y, 0);
  points->InsertNextPoint(x1, y, 0);
  points->InsertNextPoint(x1, y + tick, 0);
  vtkNew<vtkCellArray> lines;
  const vtkIdType ids[4] = { 0, 1, 2, 3 };
  lines->InsertNextCell(4, ids);
  vtkNew<vtkPolyData> bar;
  bar->SetPoints(points);
  bar->SetLines(lines);
  this->ScaleMapper->SetInputData(bar);
  char label[64];
  std::snprintf(label, sizeof(label), "%g mm", millimetres);
  this->ScaleText->SetInput(label);
  this->ScaleText->SetPosition(0.5 * (x0 + x1), y + 5.0);
}

void BenderView::CameraInteractionCallback(vtkObject*, unsigned long event, void* clientData, void*)
{
  auto* self = static_cast<BenderView*>(clientData);
  if (event == vtkCommand::StartInteractionEvent)
  {
    self->startCameraInteraction();
  }
  else
  {
    self->endCameraInteraction();
  }
}

void BenderView::setLevelOfDetail(vtkAlgorithmOutput* proxy, std::function<bool()> dragging)
{
  if (proxy)
  {
    this->ProxyMapper->SetInputConnection(proxy);
  }
  else
  {
    this->ProxyMapper->RemoveAllInputConnections(0);
  }
  this->HasProxy = proxy != nullptr;
  this->DraggingProxy = std::move(dragging);
  this->chooseLevelOfDetail();
}

void BenderView::startCameraInteraction()
{
  // The surface as committed (the live output's input has the same number of triangles).
  vtkPolyData* surface = vtkPolyData::SafeDownCast(this->SurfaceMapper->GetInput());
  this->Rotating = this->HasProxy && surface && surface->GetNumberOfPolys() > this->LodThreshold;
  this->chooseLevelOfDetail();
}

void BenderView::endCameraInteraction()
{
  if (!this->Rotating)
  {
    return;
  }
  this->Rotating = false;
  this->chooseLevelOfDetail();
  this->render();
}

void BenderView::chooseLevelOfDetail()
{
  const bool dragging = this->HasProxy && this->DraggingProxy && this->DraggingProxy();
  const bool proxy = this->HasProxy && (this->Rotating || dragging);
  // Hidden, the surface's mapper does not pull the session's full-resolution warp.
  this->ProxyActor->SetVisibility(proxy);
  this->SurfaceActor->SetVisibility(!proxy);
}

bool BenderView::isShowingProxy() const
{
  return this->ProxyActor->GetVisibility() != 0;
}

vtkPolyData* BenderView::levelOfDetailProxy() const
{
  if (!this->HasProxy || !this->ProxyActor->GetVisibility())
  {
    return nullptr;
  }
  this->ProxyMapper->Update();
  return vtkPolyData::SafeDownCast(this->ProxyMapper->GetInput());
}

void BenderView::RibbonCallback(vtkObject*, unsigned long, void* clientData, void*)
{
  emit static_cast<BenderView*>(clientData)->ribbonInteraction();
}

void BenderView::PickCallback(vtkObject*, unsigned long, void* clientData, void*)
{
  static_cast<BenderView*>(clientData)->pick();
}

void BenderView::pick()
{
  if (!this->Picking)
  {
    return;
  }
  const int* position = this->Window->GetInteractor()->GetEventPosition();
  vtkNew<vtkCellPicker> picker;
  picker->SetTolerance(0.002);
  picker->PickFromListOn();
  picker->AddPickList(this->SurfaceActor);
  // The click is the pick's, not the camera's.
  this->PickObserver->SetAbortFlag(1);
  if (picker->Pick(position[0], position[1], 0, this->Renderer))
  {
    double point[3];
    picker->GetPickPosition(point);
    emit this->surfacePicked(point[0], point[1], point[2]);
  }
  else
  {
    emit this->pickMissed();
  }
}
