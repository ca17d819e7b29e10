#include "SliceView.h"

#include "SliceGeometry.h"

#include <QVTKOpenGLNativeWidget.h>

#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkImageProperty.h>
#include <vtkLookupTable.h>
#include <vtkMatrix4x4.h>
#include <vtkPointData.h>
#include <vtkProperty.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>
#include <cstring>

SliceViews::View::View(SliceViews* owner, int index, vtkLookupTable* maskColours)
  : owner(owner)
  , index(index)
{
  // LPS: axial seen from the feet, coronal from the front, sagittal from the left.
  const double directions[3][3] = { { 0, 0, 1 }, { 0, 1, 0 }, { -1, 0, 0 } };
  const double ups[3][3] = { { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, 1 } };
  this->widget = new QVTKOpenGLNativeWidget(owner);
  this->widget->setObjectName(QString("slice%1").arg(SliceNames[index]));
  this->widget->setToolTip(
    QString("%1 slice: a left click or drag moves the cursor (the other slices follow it); "
            "the mouse wheel or Up/Down moves the slice; Shift+left drag sets the "
            "window/level, right drag zooms, middle drag pans, R frames the slice again")
      .arg(SliceNames[index]));
  this->widget->setRenderWindow(this->window);
  this->window->AddRenderer(this->renderer);
  this->renderer->SetBackground(0.05, 0.05, 0.07);
  this->mapper->SliceFacesCameraOn();
  this->mapper->SliceAtFocalPointOn();
  this->slice->SetMapper(this->mapper);
  this->overlayMapper->SliceFacesCameraOn();
  this->overlayMapper->SliceAtFocalPointOn();
  this->overlay->SetMapper(this->overlayMapper);
  this->overlay->GetProperty()->SetLookupTable(maskColours);
  this->overlay->GetProperty()->SetInterpolationTypeToNearest();
  this->overlay->GetProperty()->UseLookupTableScalarRangeOn();
  this->overlay->PickableOff();
  this->style->SetInteractionModeToImageSlicing();
  // The window/level drag sets the volume's slice (the first image), not the mask's (the
  // style's default, the topmost image, is the mask overlay).
  this->style->SetCurrentImageNumber(0);
  this->style->MoveCursor = [owner, index](int x, int y)
  {
    double position[3];
    owner->displayToCursor(index, x, y, position);
    owner->setCursor(position);
  };
  this->window->GetInteractor()->SetInteractorStyle(this->style);
  this->crosshairMapper->SetInputData(this->crosshairData);
  this->crosshairMapper->SetScalarModeToUseCellData();
  this->crosshair->SetMapper(this->crosshairMapper);
  this->crosshair->GetProperty()->SetLineWidth(1.5);
  this->crosshair->GetProperty()->LightingOff();
  this->crosshair->PickableOff();
  this->inputObserver->SetCallback(&View::OnInput);
  this->inputObserver->SetClientData(this);
  for (unsigned long event : { vtkCommand::MouseWheelForwardEvent,
         vtkCommand::MouseWheelBackwardEvent,
         vtkCommand::KeyPressEvent,
         vtkCommand::CharEvent })
  {
    this->window->GetInteractor()->AddObserver(event, this->inputObserver, 1.0f);
  }
  this->renderObserver->SetCallback(&View::BeforeRender);
  this->renderObserver->SetClientData(this);
  this->renderer->AddObserver(vtkCommand::StartEvent, this->renderObserver);
  this->annotation->SetMaximumFontSize(16);
  this->annotation->SetLinearFontScaleFactor(2);
  this->annotation->SetNonlinearFontScaleFactor(1);
  this->annotation->GetTextProperty()->SetColor(0.95, 0.85, 0.35);
  this->annotation->GetTextProperty()->ShadowOn();
  std::copy(directions[index], directions[index] + 3, this->viewDirection);
  std::copy(ups[index], ups[index] + 3, this->viewUp);
}

void SliceViews::View::OnInput(vtkObject* caller, unsigned long event, void* clientData, void*)
{
  auto* view = static_cast<SliceViews::View*>(clientData);
  auto* interactor = vtkRenderWindowInteractor::SafeDownCast(caller);
  int steps = 0;
  if (event == vtkCommand::MouseWheelForwardEvent)
  {
    steps = 1;
  }
  else if (event == vtkCommand::MouseWheelBackwardEvent)
  {
    steps = -1;
  }
  else if (event == vtkCommand::KeyPressEvent && interactor && interactor->GetKeySym())
  {
    const char* key = interactor->GetKeySym();
    steps = (!std::strcmp(key, "Up") || !std::strcmp(key, "Prior"))
      ? 1
      : ((!std::strcmp(key, "Down") || !std::strcmp(key, "Next")) ? -1 : 0);
  }
  else if (event == vtkCommand::CharEvent && interactor)
  {
    // vtkInteractorStyleImage's x / y / z keys would turn the view to VTK's own axes.
    const char c = interactor->GetKeyCode();
    if (c == 'x' || c == 'X' || c == 'y' || c == 'Y' || c == 'z' || c == 'Z')
    {
      view->inputObserver->SetAbortFlag(1);
    }
    else if (c == 'r' || c == 'R')
    {
      // Its r (reset camera) would centre the slice on the props, off the cursor.
      view->inputObserver->SetAbortFlag(1);
      view->owner->resetView(view->index);
    }
    return;
  }
  if (steps != 0 && view->owner->hasVolume())
  {
    view->owner->moveSlice(view->index, steps);
    view->inputObserver->SetAbortFlag(1);
  }
}

void SliceViews::View::BeforeRender(vtkObject*, unsigned long, void* clientData, void*)
{
  auto* view = static_cast<View*>(clientData);
  const int* size = view->renderer->GetSize();
  if (size[0] != view->fittedSize[0] || size[1] != view->fittedSize[1])
  {
    view->fit(); // first frame, or the pane was resized
  }
  view->owner->updateAnnotation(view->index);
}

void SliceViews::View::fit()
{
  const int* size = this->renderer->GetSize();
  if (!this->owner->hasVolume() || size[0] <= 0 || size[1] <= 0)
  {
    return;
  }
  const double* d = this->viewDirection;
  const double* u = this->viewUp;
  const double r[3] = {
    d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2], d[0] * u[1] - d[1] * u[0]
  };
  double bounds[6];
  this->owner->volumeBounds(bounds);
  double width = 0.0, height = 0.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    const double extent = bounds[2 * axis + 1] - bounds[2 * axis];
    width += std::abs(r[axis]) * extent;
    height += std::abs(u[axis]) * extent;
  }
  const double aspect = static_cast<double>(size[0]) / size[1];
  vtkCamera* camera = this->renderer->GetActiveCamera();
  camera->SetParallelScale(1.04 * std::max(0.5 * height, 0.5 * width / aspect));
  this->fittedSize[0] = size[0];
  this->fittedSize[1] = size[1];
}

void SliceViews::View::lookAt(const double centre[3], double distance)
{
  vtkCamera* camera = this->renderer->GetActiveCamera();
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0] - distance * this->viewDirection[0],
    centre[1] - distance * this->viewDirection[1],
    centre[2] - distance * this->viewDirection[2]);
  camera->SetViewUp(this->viewUp);
}

void SliceViews::View::show(vtkImageData* volume,
  vtkImageData* mask,
  const double bounds[6],
  const double cursor[3])
{
  this->renderer->RemoveAllViewProps();
  this->fittedSize[0] = this->fittedSize[1] = 0;
  if (!volume)
  {
    return;
  }
  this->mapper->SetInputData(Unplaced(volume));
  this->slice->SetUserMatrix(Placement(volume));
  double range[2];
  RobustRange(volume->GetPointData()->GetScalars(), range);
  this->slice->GetProperty()->SetColorWindow(std::max(range[1] - range[0], 1e-6));
  this->slice->GetProperty()->SetColorLevel(0.5 * (range[0] + range[1]));
  this->renderer->AddViewProp(this->slice);
  if (mask)
  {
    this->overlayMapper->SetInputData(Unplaced(mask));
    this->overlay->SetUserMatrix(Placement(mask));
    this->renderer->AddViewProp(this->overlay);
  }
  this->renderer->AddViewProp(this->crosshair);
  this->renderer->AddViewProp(this->annotation);
  // Framed on the box's centre, sliced through the cursor.
  double centre[3] = {
    0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5])
  };
  const int axis = SliceAxis(this->index);
  centre[axis] = cursor[axis];
  vtkCamera* camera = this->renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  const double distance =
    2.0 * (bounds[1] - bounds[0] + bounds[3] - bounds[2] + bounds[5] - bounds[4]) + 1.0;
  this->lookAt(centre, distance);
  camera->SetClippingRange(0.5 * distance, 1.5 * distance);
  this->fit();
}
