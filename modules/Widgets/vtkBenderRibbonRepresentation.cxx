#include "vtkBenderRibbonRepresentation.h"

#include "GeometryErrors.h"
#include "vtkBenderRegionOutline.h"
#include "vtkBenderRibbonSource.h"

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkConeSource.h>
#include <vtkCubeSource.h>
#include <vtkInteractorObserver.h>
#include <vtkObjectFactory.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPropCollection.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkViewport.h>
#include <vtkWindow.h>

#include "Ribbon.h"

#include <algorithm>
#include <cmath>
#include <exception>

vtkStandardNewMacro(vtkBenderRibbonRepresentation);

namespace
{
using bender::Vec3;

Vec3 ToVec(const double p[3])
{
  return { p[0], p[1], p[2] };
}

// The part of v orthogonal to the unit t, normalised; `fallback` when v is (nearly) along t.
Vec3 OrthogonalPart(const Vec3& v, const Vec3& t, const Vec3& fallback)
{
  const Vec3 w = v - bender::Dot(v, t) * t;
  const double n = bender::Norm(w);
  return n > 1e-12 ? (1.0 / n) * w : fallback;
}

// A unit vector orthogonal to the unit t.
Vec3 AnyOrthogonal(const Vec3& t)
{
  const Vec3 axis = std::abs(t.x) < 0.9 ? Vec3{ 1, 0, 0 } : Vec3{ 0, 1, 0 };
  return bender::Normalized(bender::Cross(t, axis));
}

// The role of a handle: 0 end, 1 tangent, 2 twist, -1 none.
int RoleOf(int handle)
{
  switch (handle)
  {
    case vtkBenderRibbonRepresentation::StartPosition:
    case vtkBenderRibbonRepresentation::EndPosition:
      return 0;
    case vtkBenderRibbonRepresentation::StartTangent:
    case vtkBenderRibbonRepresentation::EndTangent:
      return 1;
    case vtkBenderRibbonRepresentation::StartNormal:
    case vtkBenderRibbonRepresentation::EndNormal:
      return 2;
    default:
      return -1;
  }
}

// A safe unit direction: the input normalised, or `fallback` for a zero/non-finite vector.
Vec3 UnitOr(const Vec3& v, const Vec3& fallback)
{
  const double n = bender::Norm(v);
  return (std::isfinite(n) && n > 1e-300) ? (1.0 / n) * v : fallback;
}
}

vtkBenderRibbonRepresentation::vtkBenderRibbonRepresentation()
{
  this->InteractionState = Outside;
  this->Source = vtkSmartPointer<vtkBenderRibbonSource>::New();
  this->Source->SetResolution(96);
  this->Source->SetTubeSides(32);

  this->StripMapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  this->StripMapper->SetInputConnection(this->Source->GetOutputPort(0));
  this->StripActor = vtkSmartPointer<vtkActor>::New();
  this->StripActor->SetMapper(this->StripMapper);
  this->StripActor->GetProperty()->SetColor(1.0, 0.78, 0.2);
  this->StripActor->GetProperty()->SetAmbient(0.6);
  this->StripActor->GetProperty()->SetDiffuse(0.6);

  this->RegionMapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  this->RegionMapper->SetInputConnection(this->Source->GetOutputPort(2));
  this->RegionActor = vtkSmartPointer<vtkActor>::New();
  this->RegionActor->SetMapper(this->RegionMapper);
  this->RegionActor->GetProperty()->SetColor(0.35, 0.65, 1.0);
  this->RegionActor->GetProperty()->SetOpacity(this->RegionOpacity);
  // Front faces only: a translucent closed tube drawn without depth peeling shows its back
  // faces through the front ones in arbitrary order (stripes); culling keeps it clean.
  this->RegionActor->GetProperty()->BackfaceCullingOn();
  this->RegionActor->PickableOff();

  // The region's outline as seen from the camera: the boundary of the discs of radius R
  // around the wire's projection (vtkBenderRegionOutline), never crossing itself.
  this->CageSource = vtkSmartPointer<vtkBenderRibbonSource>::New();
  this->CageSource->SetResolution(48);
  this->CageSource->SetTubeSides(32);
  this->CageSource->SetWidth(0.0);
  this->Outline = vtkSmartPointer<vtkBenderRegionOutline>::New();
  this->Outline->SetInputConnection(this->CageSource->GetOutputPort(1));
  this->CageMapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  this->CageMapper->SetInputConnection(this->Outline->GetOutputPort());
  this->CageActor = vtkSmartPointer<vtkActor>::New();
  this->CageActor->SetMapper(this->CageMapper);
  this->CageActor->GetProperty()->SetLineWidth(2.0);
  this->CageActor->GetProperty()->SetColor(0.45, 0.75, 1.0);
  this->CageActor->GetProperty()->LightingOff();
  this->CageActor->PickableOff();

  this->Lines = vtkSmartPointer<vtkPolyData>::New();
  this->LinesMapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  this->LinesMapper->SetInputData(this->Lines);
  this->LinesActor = vtkSmartPointer<vtkActor>::New();
  this->LinesActor->SetMapper(this->LinesMapper);
  this->LinesActor->GetProperty()->SetLineWidth(2.0);
  this->LinesActor->GetProperty()->SetColor(0.9, 0.9, 0.9);
  this->LinesActor->GetProperty()->LightingOff();

  // End handles: spheres; tangent handles: cones pointing along the tangent, away from the
  // ribbon; twist handles: cubes. One colour per role, yellow under the cursor, red when invalid.
  this->Sphere = vtkSmartPointer<vtkSphereSource>::New();
  this->Sphere->SetThetaResolution(20);
  this->Sphere->SetPhiResolution(14);
  this->SphereMapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  this->SphereMapper->SetInputConnection(this->Sphere->GetOutputPort());
  for (int e = 0; e < 2; ++e)
  {
    this->Cones[e] = vtkSmartPointer<vtkConeSource>::New();
    this->Cones[e]->SetResolution(20);
    this->Cones[e]->CappingOn();
    this->ConeMappers[e] = vtkSmartPointer<vtkPolyDataMapper>::New();
    this->ConeMappers[e]->SetInputConnection(this->Cones[e]->GetOutputPort());
  }
  this->Cube = vtkSmartPointer<vtkCubeSource>::New();
  this->CubeMapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  this->CubeMapper->SetInputConnection(this->Cube->GetOutputPort());

  const double roleColours[3][3] = { { 0.15, 0.55, 1.0 }, { 0.2, 0.85, 0.3 }, { 0.9, 0.3, 0.9 } };
  for (int role = 0; role < 3; ++role)
  {
    this->RoleProperties[role] = vtkSmartPointer<vtkProperty>::New();
    this->RoleProperties[role]->SetColor(
      roleColours[role][0], roleColours[role][1], roleColours[role][2]);
    this->RoleProperties[role]->SetAmbient(0.35);
    this->RoleProperties[role]->SetSpecular(0.3);
  }
  this->SelectedProperty = vtkSmartPointer<vtkProperty>::New();
  this->SelectedProperty->SetColor(1.0, 1.0, 0.2);
  this->SelectedProperty->SetAmbient(0.5);
  this->InvalidProperty = vtkSmartPointer<vtkProperty>::New();
  this->InvalidProperty->SetColor(1.0, 0.15, 0.15);
  this->HandleActors[Outside] = nullptr;
  for (int h = StartPosition; h < NumberOfHandles; ++h)
  {
    this->HandleActors[h] = vtkSmartPointer<vtkActor>::New();
    switch (RoleOf(h))
    {
      case 0:
        this->HandleActors[h]->SetMapper(this->SphereMapper);
        break;
      case 1:
        this->HandleActors[h]->SetMapper(this->ConeMappers[h == StartTangent ? 0 : 1]);
        break;
      default:
        this->HandleActors[h]->SetMapper(this->CubeMapper);
        break;
    }
    this->HandleActors[h]->SetProperty(this->RoleProperties[RoleOf(h)]);
  }

  this->HoverLabel = vtkSmartPointer<vtkTextActor>::New();
  vtkTextProperty* text = this->HoverLabel->GetTextProperty();
  text->SetFontSize(15);
  text->SetColor(1.0, 1.0, 0.75);
  text->BoldOn();
  text->ShadowOn();
  text->SetBackgroundColor(0.0, 0.0, 0.0);
  text->SetBackgroundOpacity(0.55);
  this->HoverLabel->VisibilityOff();
  this->HoverLabel->PickableOff();

  this->Ribbon.start.position = { 0, 0, 0 };
  this->Ribbon.end.position = { 1, 0, 0 };
  std::fill(this->Bounds, this->Bounds + 6, 0.0);
  this->BuildRepresentation();
}

vtkBenderRibbonRepresentation::~vtkBenderRibbonRepresentation() = default;

vtkActor* vtkBenderRibbonRepresentation::GetStripActor()
{
  return this->StripActor;
}

vtkBenderRibbonSource* vtkBenderRibbonRepresentation::GetRibbonSource()
{
  return this->Source;
}

const char* vtkBenderRibbonRepresentation::GetHandleRole(int handle)
{
  static const char* const roles[3] = { "end", "tangent", "twist" };
  const int role = RoleOf(handle);
  return role < 0 ? "" : roles[role];
}

const char* vtkBenderRibbonRepresentation::GetHandleHint(int handle)
{
  static const char* const hints[3] = {
    "end: drag to move", "tangent: drag to bend", "twist: drag to twist"
  };
  const int role = RoleOf(handle);
  return role < 0 ? "" : hints[role];
}

const char* vtkBenderRibbonRepresentation::GetHoverText() const
{
  return this->Valid ? GetHandleHint(this->InteractionState) : "";
}

vtkActor* vtkBenderRibbonRepresentation::GetHandleActor(int handle)
{
  return (handle > Outside && handle < NumberOfHandles) ? this->HandleActors[handle].GetPointer()
                                                        : nullptr;
}

void vtkBenderRibbonRepresentation::SetRibbon(const bender::RibbonSpec& ribbon)
{
  this->Ribbon = ribbon;
  this->Modified();
  this->BuildRepresentation();
}

void vtkBenderRibbonRepresentation::SetRadius(double radius)
{
  this->Radius = std::isfinite(radius) ? std::max(0.0, radius) : 0.0;
  this->Modified();
  this->BuildRepresentation();
}

void vtkBenderRibbonRepresentation::SetRegionVisibility(bool visible)
{
  this->RegionVisibility = visible;
  this->Modified();
  this->BuildRepresentation();
}

void vtkBenderRibbonRepresentation::SetRegionOpacity(double opacity)
{
  this->RegionOpacity = std::isfinite(opacity) ? std::min(1.0, std::max(0.0, opacity)) : 0.0;
  this->RegionActor->GetProperty()->SetOpacity(this->RegionOpacity);
  this->Modified();
  this->BuildRepresentation();
}

void vtkBenderRibbonRepresentation::SetHandleLength(double length)
{
  if (std::isfinite(length) && length > 0.0)
  {
    this->HandleLength = length;
    this->Modified();
    this->BuildRepresentation();
  }
}

void vtkBenderRibbonRepresentation::SetHandleRadius(double radius)
{
  if (std::isfinite(radius) && radius > 0.0)
  {
    this->HandleRadius = radius;
    this->Modified();
    this->BuildRepresentation();
  }
}

void vtkBenderRibbonRepresentation::SetStripWidth(double width)
{
  this->Source->SetWidth(width);
  this->Modified();
}

double vtkBenderRibbonRepresentation::GetStripWidth() const
{
  return this->Source->GetWidth();
}

void vtkBenderRibbonRepresentation::UpdateValidity()
{
  try
  {
    bender::Ribbon check(this->Ribbon);
    this->Valid = true;
    this->LastError.clear();
  }
  catch (const bender::GeometryError& e) // an invalid ribbon (InvalidRibbonError)
  {
    this->Valid = false;
    this->LastError = e.what();
  }
}

void vtkBenderRibbonRepresentation::GetHandlePosition(int handle, double position[3]) const
{
  const bender::RibbonEnd& start = this->Ribbon.start;
  const bender::RibbonEnd& end = this->Ribbon.end;
  const Vec3 t0 = UnitOr(start.tangent, { 1, 0, 0 });
  const Vec3 t1 = UnitOr(end.tangent, { 1, 0, 0 });
  const Vec3 n0 = OrthogonalPart(start.normal, t0, AnyOrthogonal(t0));
  const Vec3 n1 = OrthogonalPart(end.normal, t1, AnyOrthogonal(t1));
  const double l = this->HandleLength;
  Vec3 p{ 0, 0, 0 };
  switch (handle)
  {
    case StartPosition:
      p = start.position;
      break;
    case EndPosition:
      p = end.position;
      break;
    case StartTangent:
      p = start.position - l * t0;
      break;
    case EndTangent:
      p = end.position + l * t1;
      break;
    case StartNormal:
      p = start.position + l * n0;
      break;
    case EndNormal:
      p = end.position + l * n1;
      break;
    default:
      break;
  }
  position[0] = p.x;
  position[1] = p.y;
  position[2] = p.z;
}

bool vtkBenderRibbonRepresentation::MoveHandle(int handle, const double position[3])
{
  const Vec3 target = ToVec(position);
  if (!bender::IsFinite(target))
  {
    return false;
  }
  bender::RibbonEnd& start = this->Ribbon.start;
  bender::RibbonEnd& end = this->Ribbon.end;
  switch (handle)
  {
    case StartPosition:
      start.position = target;
      break;
    case EndPosition:
      end.position = target;
      break;
    case StartTangent:
    case EndTangent:
    {
      bender::RibbonEnd& e = handle == StartTangent ? start : end;
      const Vec3 direction = handle == StartTangent ? e.position - target : target - e.position;
      if (bender::Norm(direction) <= 1e-9 * std::max(1.0, bender::Norm(e.position)))
      {
        return false;
      }
      const Vec3 t = bender::Normalized(direction);
      e.tangent = t;
      e.normal = OrthogonalPart(e.normal, t, AnyOrthogonal(t));
      break;
    }
    case StartNormal:
    case EndNormal:
    {
      bender::RibbonEnd& e = handle == StartNormal ? start : end;
      const Vec3 t = UnitOr(e.tangent, { 1, 0, 0 });
      const Vec3 w = target - e.position;
      const Vec3 across = w - bender::Dot(w, t) * t;
      if (bender::Norm(across) <= 1e-9 * std::max(1.0, bender::Norm(e.position)))
      {
        return false;
      }
      e.normal = bender::Normalized(across);
      break;
    }
    default:
      return false;
  }
  this->Modified();
  this->BuildRepresentation();
  return true;
}

void vtkBenderRibbonRepresentation::PlaceWidget(double bounds[6])
{
  double centre[3];
  double adjusted[6];
  this->AdjustBounds(bounds, adjusted, centre);
  double extent[3] = { bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] };
  const int axis = static_cast<int>(std::max_element(extent, extent + 3) - extent);
  const double length = std::max(extent[axis], 1e-6);
  const double half = 0.25 * length;
  bender::RibbonSpec ribbon;
  Vec3 direction{ 0, 0, 0 };
  (axis == 0 ? direction.x : (axis == 1 ? direction.y : direction.z)) = 1.0;
  const Vec3 c{
    0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5])
  };
  ribbon.start.position = c - half * direction;
  ribbon.end.position = c + half * direction;
  ribbon.start.tangent = ribbon.end.tangent = direction;
  ribbon.start.normal = ribbon.end.normal = AnyOrthogonal(direction);
  this->HandleLength = 0.08 * length;
  this->HandleRadius = 0.015 * length;
  this->Source->SetWidth(0.02 * length);
  this->Placed = 1;
  this->SetRibbon(ribbon);
}

void vtkBenderRibbonRepresentation::BuildRepresentation()
{
  this->UpdateValidity();
  this->Source->SetRibbon(this->Ribbon);
  // The region's tube (the source's third output, 96 x 32 rings) only when it is drawn: the
  // outline comes from the cage's coarser tube, and a tube made on every move for nothing cost
  // the demo's drag about 2 ms a frame.
  this->Source->SetRadius(this->RegionVisibility && this->RegionOpacity > 0.0 ? this->Radius : 0.0);
  this->CageSource->SetRibbon(this->Ribbon);
  this->CageSource->SetRadius(this->RegionVisibility ? this->Radius : 0.0);
  this->Outline->SetRadius(this->RegionVisibility ? this->Radius : 0.0);
  // The end handles a little larger than the others: they are the ones to grab first.
  const double r = this->HandleRadius;
  this->Sphere->SetRadius(1.25 * r);
  this->Cube->SetXLength(1.5 * r);
  this->Cube->SetYLength(1.5 * r);
  this->Cube->SetZLength(1.5 * r);

  // Arms from the end points to their tangent and normal handles; for an invalid ribbon also
  // the straight line between the ends, drawn in red.
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> lines;
  auto addLine = [&](const double a[3], const double b[3])
  {
    const vtkIdType ids[2] = { points->InsertNextPoint(a), points->InsertNextPoint(b) };
    lines->InsertNextCell(2, ids);
  };
  double p[NumberOfHandles][3];
  for (int h = StartPosition; h < NumberOfHandles; ++h)
  {
    this->GetHandlePosition(h, p[h]);
    this->HandleActors[h]->SetPosition(p[h]);
  }
  {
    // The cones point away from the ribbon, along the tangent lines.
    const Vec3 t0 = UnitOr(this->Ribbon.start.tangent, { 1, 0, 0 });
    const Vec3 t1 = UnitOr(this->Ribbon.end.tangent, { 1, 0, 0 });
    const Vec3 directions[2] = { -1.0 * t0, t1 };
    for (int e = 0; e < 2; ++e)
    {
      this->Cones[e]->SetHeight(2.6 * r);
      this->Cones[e]->SetRadius(1.1 * r);
      this->Cones[e]->SetCenter(0, 0, 0);
      this->Cones[e]->SetDirection(directions[e].x, directions[e].y, directions[e].z);
    }
  }
  addLine(p[StartPosition], p[StartTangent]);
  addLine(p[StartPosition], p[StartNormal]);
  addLine(p[EndPosition], p[EndTangent]);
  addLine(p[EndPosition], p[EndNormal]);
  if (!this->Valid)
  {
    addLine(p[StartPosition], p[EndPosition]);
  }
  this->Lines->SetPoints(points);
  this->Lines->SetLines(lines);
  this->Lines->Modified();
  this->LinesActor->GetProperty()->SetColor(
    this->Valid ? 0.9 : 1.0, this->Valid ? 0.9 : 0.15, this->Valid ? 0.9 : 0.15);
  for (int h = StartPosition; h < NumberOfHandles; ++h)
  {
    const bool selected = this->InteractionState == h;
    this->HandleActors[h]->SetProperty(selected
        ? this->SelectedProperty.GetPointer()
        : (this->Valid ? this->RoleProperties[RoleOf(h)].GetPointer()
                       : this->InvalidProperty.GetPointer()));
  }
  const char* hint = this->GetHoverText();
  this->HoverLabel->SetInput(hint);
  this->HoverLabel->SetVisibility(hint[0] != '\0');
  this->Source->Update();
  this->CageSource->Update();
  this->BuildTime.Modified();
}

int vtkBenderRibbonRepresentation::ComputeInteractionState(int X, int Y, int)
{
  this->InteractionState = Outside;
  // Without a camera there is no projection yet (the widget asks when it is enabled).
  if (!this->Renderer || !this->Renderer->IsActiveCameraCreated())
  {
    return this->InteractionState;
  }
  double best = static_cast<double>(this->Tolerance) * this->Tolerance;
  for (int h = StartPosition; h < NumberOfHandles; ++h)
  {
    double world[3], display[3];
    this->GetHandlePosition(h, world);
    vtkInteractorObserver::ComputeWorldToDisplay(
      this->Renderer, world[0], world[1], world[2], display);
    const double dx = display[0] - X;
    const double dy = display[1] - Y;
    // Ties go to the position handles (listed first), which matter most.
    if (dx * dx + dy * dy < best)
    {
      best = dx * dx + dy * dy;
      this->InteractionState = h;
    }
  }
  return this->InteractionState;
}

void vtkBenderRibbonRepresentation::StartWidgetInteraction(double eventPosition[2])
{
  if (!this->Renderer || this->InteractionState == Outside)
  {
    return;
  }
  double world[3], display[3], cursor[4];
  this->GetHandlePosition(this->InteractionState, world);
  vtkInteractorObserver::ComputeWorldToDisplay(
    this->Renderer, world[0], world[1], world[2], display);
  this->DragDepth = display[2];
  vtkInteractorObserver::ComputeDisplayToWorld(
    this->Renderer, eventPosition[0], eventPosition[1], this->DragDepth, cursor);
  for (int c = 0; c < 3; ++c)
  {
    this->DragOffset[c] = world[c] - cursor[c];
  }
  this->BuildRepresentation();
}

void vtkBenderRibbonRepresentation::WidgetInteraction(double eventPosition[2])
{
  if (!this->Renderer || this->InteractionState == Outside)
  {
    return;
  }
  double cursor[4];
  vtkInteractorObserver::ComputeDisplayToWorld(
    this->Renderer, eventPosition[0], eventPosition[1], this->DragDepth, cursor);
  const double target[3] = { cursor[0] + this->DragOffset[0],
    cursor[1] + this->DragOffset[1],
    cursor[2] + this->DragOffset[2] };
  this->MoveHandle(this->InteractionState, target);
}

void vtkBenderRibbonRepresentation::EndWidgetInteraction(double*)
{
  this->InteractionState = Outside;
  this->BuildRepresentation();
}

void vtkBenderRibbonRepresentation::Highlight(int highlight)
{
  if (!highlight)
  {
    this->InteractionState = Outside;
  }
  this->BuildRepresentation();
}

vtkPolyData* vtkBenderRibbonRepresentation::GetRegionOutline()
{
  this->Outline->Update();
  return this->Outline->GetOutput();
}

double* vtkBenderRibbonRepresentation::GetBounds()
{
  this->BuildRepresentation();
  double b[6];
  this->Lines->GetBounds(this->Bounds);
  if (this->Valid && this->Radius > 0.0 && this->RegionVisibility)
  {
    this->CageSource->Update();
    this->CageSource->GetOutput(2)->GetBounds(b);
    for (int i = 0; i < 3; ++i)
    {
      this->Bounds[2 * i] = std::min(this->Bounds[2 * i], b[2 * i]);
      this->Bounds[2 * i + 1] = std::max(this->Bounds[2 * i + 1], b[2 * i + 1]);
    }
  }
  return this->Bounds;
}

void vtkBenderRibbonRepresentation::GetActors(vtkPropCollection* actors)
{
  actors->AddItem(this->StripActor);
  actors->AddItem(this->RegionActor);
  actors->AddItem(this->CageActor);
  actors->AddItem(this->LinesActor);
  for (int h = StartPosition; h < NumberOfHandles; ++h)
  {
    actors->AddItem(this->HandleActors[h]);
  }
}

void vtkBenderRibbonRepresentation::ReleaseGraphicsResources(vtkWindow* window)
{
  this->StripActor->ReleaseGraphicsResources(window);
  this->RegionActor->ReleaseGraphicsResources(window);
  this->CageActor->ReleaseGraphicsResources(window);
  this->LinesActor->ReleaseGraphicsResources(window);
  this->HoverLabel->ReleaseGraphicsResources(window);
  for (int h = StartPosition; h < NumberOfHandles; ++h)
  {
    this->HandleActors[h]->ReleaseGraphicsResources(window);
  }
}

int vtkBenderRibbonRepresentation::RenderOpaqueGeometry(vtkViewport* viewport)
{
  int count = 0;
  if (this->Valid)
  {
    count += this->StripActor->RenderOpaqueGeometry(viewport);
    vtkRenderer* renderer = vtkRenderer::SafeDownCast(viewport);
    if (this->Radius > 0.0 && this->RegionVisibility && renderer &&
      renderer->IsActiveCameraCreated())
    {
      this->Outline->SetCamera(renderer->GetActiveCamera());
      count += this->CageActor->RenderOpaqueGeometry(viewport);
    }
  }
  count += this->LinesActor->RenderOpaqueGeometry(viewport);
  for (int h = StartPosition; h < NumberOfHandles; ++h)
  {
    count += this->HandleActors[h]->RenderOpaqueGeometry(viewport);
  }
  if (this->PlaceHoverLabel(viewport))
  {
    count += this->HoverLabel->RenderOpaqueGeometry(viewport);
  }
  return count;
}

int vtkBenderRibbonRepresentation::RenderTranslucentPolygonalGeometry(vtkViewport* viewport)
{
  if (!this->HasTranslucentPolygonalGeometry())
  {
    return 0;
  }
  return this->RegionActor->RenderTranslucentPolygonalGeometry(viewport);
}

bool vtkBenderRibbonRepresentation::PlaceHoverLabel(vtkViewport* viewport)
{
  vtkRenderer* renderer = vtkRenderer::SafeDownCast(viewport);
  if (!this->HoverLabel->GetVisibility() || !renderer || !renderer->IsActiveCameraCreated())
  {
    return false;
  }
  // Beside the handle, up and to the right, kept inside the viewport.
  double world[3], display[3];
  this->GetHandlePosition(this->InteractionState, world);
  vtkInteractorObserver::ComputeWorldToDisplay(renderer, world[0], world[1], world[2], display);
  const int* size = renderer->GetSize();
  const int* origin = renderer->GetOrigin();
  double x = display[0] - origin[0] + 16.0;
  double y = display[1] - origin[1] + 12.0;
  x = std::max(2.0, std::min(x, static_cast<double>(size[0]) - 170.0));
  y = std::max(2.0, std::min(y, static_cast<double>(size[1]) - 24.0));
  this->HoverLabel->SetPosition(x, y);
  return true;
}

int vtkBenderRibbonRepresentation::RenderOverlay(vtkViewport* viewport)
{
  // The text's texture was made in RenderOpaqueGeometry.
  return this->HoverLabel->GetVisibility() ? this->HoverLabel->RenderOverlay(viewport) : 0;
}

vtkTypeBool vtkBenderRibbonRepresentation::HasTranslucentPolygonalGeometry()
{
  return this->Valid && this->Radius > 0.0 && this->RegionVisibility && this->RegionOpacity > 0.0
    ? 1
    : 0;
}

void vtkBenderRibbonRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Start: (" << this->Ribbon.start.position.x << ", "
     << this->Ribbon.start.position.y << ", " << this->Ribbon.start.position.z << ")\n";
  os << indent << "End: (" << this->Ribbon.end.position.x << ", " << this->Ribbon.end.position.y
     << ", " << this->Ribbon.end.position.z << ")\n";
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "HandleLength: " << this->HandleLength << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "Valid: " << this->Valid << (this->Valid ? "" : " (" + this->LastError + ")")
     << "\n";
}
