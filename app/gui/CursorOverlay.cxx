#include "CursorOverlay.h"

#include "SliceGeometry.h"

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellPicker.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace
{
constexpr int ClickTolerance = 3; // pixels between press and release for a click
}

CursorOverlay::CursorOverlay(vtkRenderer* layer,
  vtkRenderer* pickRenderer,
  vtkProp* pickable,
  QObject* parent)
  : QObject(parent)
  , Layer(layer)
  , PickRenderer(pickRenderer)
  , Pickable(pickable)
{
  this->CrossMapper->SetInputData(this->CrossData);
  this->CrossMapper->ScalarVisibilityOff();
  this->Cross->SetMapper(this->CrossMapper);
  this->Cross->GetProperty()->SetColor(0.97, 0.97, 0.97);
  this->Cross->GetProperty()->SetLineWidth(2.0);
  this->Cross->GetProperty()->LightingOff();
  this->Cross->PickableOff();
  this->PlaneMapper->SetInputData(this->PlaneData);
  this->PlaneMapper->SetScalarModeToUseCellData();
  this->Planes->SetMapper(this->PlaneMapper);
  this->Planes->GetProperty()->SetLineWidth(1.5);
  this->Planes->GetProperty()->LightingOff();
  this->Planes->PickableOff();
  this->Layer->AddActor(this->Cross);
  this->Layer->AddActor(this->Planes);
  this->MouseObserver->SetCallback(&CursorOverlay::OnMouse);
  this->MouseObserver->SetClientData(this);
  // Passive: it sees the release even when the camera style has grabbed the mouse (a
  // Shift+press starts its pan), and it never takes an event.
  this->MouseObserver->PassiveObserverOn();
  if (vtkRenderWindow* window = this->Layer->GetRenderWindow())
  {
    this->Interactor = window->GetInteractor();
    if (this->Interactor)
    {
      // Before the camera style, the ribbon widget and the view's own picking (priority 10);
      // the events are only watched, never taken.
      this->Interactor->AddObserver(vtkCommand::LeftButtonPressEvent, this->MouseObserver, 20.0f);
      this->Interactor->AddObserver(vtkCommand::LeftButtonReleaseEvent, this->MouseObserver, 20.0f);
    }
  }
  this->rebuild();
}

CursorOverlay::~CursorOverlay()
{
  if (this->Interactor)
  {
    this->Interactor->RemoveObserver(this->MouseObserver);
  }
  this->Layer->RemoveActor(this->Cross);
  this->Layer->RemoveActor(this->Planes);
}

void CursorOverlay::OnMouse(vtkObject* caller, unsigned long event, void* clientData, void*)
{
  auto* self = static_cast<CursorOverlay*>(clientData);
  auto* interactor = vtkRenderWindowInteractor::SafeDownCast(caller);
  if (!interactor)
  {
    return;
  }
  const int* at = interactor->GetEventPosition();
  if (event == vtkCommand::LeftButtonPressEvent)
  {
    self->Pressed = interactor->GetShiftKey() && !interactor->GetControlKey() &&
      !interactor->GetAltKey() && interactor->GetRepeatCount() == 0 &&
      !(self->Busy && self->Busy());
    self->PressedAt[0] = at[0];
    self->PressedAt[1] = at[1];
    return;
  }
  if (event != vtkCommand::LeftButtonReleaseEvent || !self->Pressed)
  {
    return;
  }
  self->Pressed = false;
  if (std::abs(at[0] - self->PressedAt[0]) > ClickTolerance ||
    std::abs(at[1] - self->PressedAt[1]) > ClickTolerance)
  {
    return; // a Shift+drag: the camera's pan
  }
  double point[3];
  if (self->pickAt(self->PressedAt[0], self->PressedAt[1], point))
  {
    emit self->picked(point[0], point[1], point[2]);
  }
}

bool CursorOverlay::pickAt(int x, int y, double point[3]) const
{
  if (!this->Pickable || !this->Pickable->GetVisibility())
  {
    return false;
  }
  vtkNew<vtkCellPicker> picker;
  picker->SetTolerance(0.002);
  picker->PickFromListOn();
  picker->AddPickList(this->Pickable);
  if (!picker->Pick(x, y, 0, this->PickRenderer))
  {
    return false;
  }
  picker->GetPickPosition(point);
  return std::isfinite(point[0]) && std::isfinite(point[1]) && std::isfinite(point[2]);
}

void CursorOverlay::setBounds(const double bounds[6])
{
  std::copy(bounds, bounds + 6, this->Bounds);
  this->rebuild();
}

void CursorOverlay::setPosition(const double position[3])
{
  std::copy(position, position + 3, this->Position);
  this->rebuild();
}

void CursorOverlay::position(double position[3]) const
{
  std::copy(this->Position, this->Position + 3, position);
}

void CursorOverlay::setStyle(Style style)
{
  this->CurrentStyle = style;
  this->rebuild();
}

bool CursorOverlay::isShown() const
{
  return this->CurrentStyle != Hidden && this->Bounds[0] <= this->Bounds[1] &&
    this->Bounds[2] <= this->Bounds[3] && this->Bounds[4] <= this->Bounds[5];
}

void CursorOverlay::rebuild()
{
  const bool shown = this->isShown();
  this->Cross->SetVisibility(shown);
  this->Planes->SetVisibility(shown && this->CurrentStyle == CrosshairAndPlanes);
  if (!shown)
  {
    return;
  }
  const double* b = this->Bounds;
  const double* p = this->Position;
  const double diagonal = std::sqrt(
    (b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  const double arm = std::max(0.06 * diagonal, 1e-3);

  // The crosshair: three segments through the cursor along L, P and S.
  vtkNew<vtkPoints> crossPoints;
  crossPoints->SetDataTypeToDouble();
  vtkNew<vtkCellArray> crossLines;
  for (int axis = 0; axis < 3; ++axis)
  {
    double a[3] = { p[0], p[1], p[2] };
    double c[3] = { p[0], p[1], p[2] };
    a[axis] -= arm;
    c[axis] += arm;
    const vtkIdType ids[2] = { crossPoints->InsertNextPoint(a), crossPoints->InsertNextPoint(c) };
    crossLines->InsertNextCell(2, ids);
  }
  this->CrossData->SetPoints(crossPoints);
  this->CrossData->SetLines(crossLines);
  this->CrossData->Modified();

  // The planes: the box's section through the cursor, one closed outline per plane.
  vtkNew<vtkPoints> planePoints;
  planePoints->SetDataTypeToDouble();
  vtkNew<vtkCellArray> planeLines;
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("Colors");
  colours->SetNumberOfComponents(3);
  for (int plane = 0; plane < 3; ++plane)
  {
    const int n = SliceAxis(plane);
    const int u = (n + 1) % 3;
    const int v = (n + 2) % 3;
    const double corners[4][2] = { { b[2 * u], b[2 * v] },
      { b[2 * u + 1], b[2 * v] },
      { b[2 * u + 1], b[2 * v + 1] },
      { b[2 * u], b[2 * v + 1] } };
    vtkIdType ids[5];
    for (int k = 0; k < 4; ++k)
    {
      double q[3];
      q[n] = p[n];
      q[u] = corners[k][0];
      q[v] = corners[k][1];
      ids[k] = planePoints->InsertNextPoint(q);
    }
    ids[4] = ids[0];
    planeLines->InsertNextCell(5, ids);
    colours->InsertNextTypedTuple(SliceColours[plane]);
  }
  this->PlaneData->SetPoints(planePoints);
  this->PlaneData->SetLines(planeLines);
  this->PlaneData->GetCellData()->SetScalars(colours);
  this->PlaneData->Modified();
}
