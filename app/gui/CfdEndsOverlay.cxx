#include "CfdEndsOverlay.h"

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCoordinate.h>
#include <vtkDataArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace
{
using P3 = std::array<double, 3>;
constexpr int DiscSides = 72;
constexpr double DiscScale = 1.5;    // disc radius / inscribed radius
constexpr double HandleScale = 0.35; // handle radius / inscribed radius
constexpr double PickPixels = 12.0;  // a press this near a handle's centre grabs it
const double InletColour[3] = { 0.93, 0.33, 0.28 };
const double OutletColour[3] = { 0.26, 0.56, 0.96 };

P3 Perpendicular(const P3& n)
{
  // The axis least aligned with n, made perpendicular to it.
  int axis = 0;
  for (int a = 1; a < 3; ++a)
  {
    if (std::abs(n[a]) < std::abs(n[axis]))
    {
      axis = a;
    }
  }
  P3 e{ { 0, 0, 0 } };
  e[axis] = 1.0;
  const double d = e[0] * n[0] + e[1] * n[1] + e[2] * n[2];
  P3 u{ { e[0] - d * n[0], e[1] - d * n[1], e[2] - d * n[2] } };
  const double length = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  return { { u[0] / length, u[1] / length, u[2] / length } };
}

P3 Cross(const P3& a, const P3& b)
{
  return { { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] } };
}

vtkSmartPointer<vtkTextActor> MakeText(const double colour[3])
{
  auto text = vtkSmartPointer<vtkTextActor>::New();
  vtkTextProperty* property = text->GetTextProperty();
  property->SetFontSize(16);
  property->BoldOn();
  property->ShadowOn();
  property->SetColor(colour[0] * 0.4 + 0.6, colour[1] * 0.4 + 0.6, colour[2] * 0.4 + 0.6);
  property->SetBackgroundColor(0.05, 0.05, 0.08);
  property->SetBackgroundOpacity(0.55);
  text->PickableOff();
  return text;
}

/// Places `text` at a model point, offset by a few pixels (so that it does not cover what it
/// names).
void PlaceText(vtkTextActor* text, const P3& at, double dx, double dy)
{
  vtkNew<vtkCoordinate> reference;
  reference->SetCoordinateSystemToWorld();
  reference->SetValue(at[0], at[1], at[2]);
  text->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
  text->GetPositionCoordinate()->SetReferenceCoordinate(reference);
  text->GetPositionCoordinate()->SetValue(dx, dy);
}
} // namespace

CfdEndsOverlay::CfdEndsOverlay(vtkRenderer* surfaceLayer, vtkRenderer* topLayer, QObject* parent)
  : QObject(parent)
  , SurfaceLayer(surfaceLayer)
  , TopLayer(topLayer ? topLayer : surfaceLayer)
{
  vtkNew<vtkPolyDataMapper> capMapper;
  capMapper->SetInputData(this->CapData);
  capMapper->SetScalarModeToUseCellData();
  // On the caps of the surface: drawn slightly in front of the coincident triangles.
  capMapper->SetResolveCoincidentTopologyToPolygonOffset();
  capMapper->SetRelativeCoincidentTopologyPolygonOffsetParameters(-4, -40);
  this->CapActor = vtkSmartPointer<vtkActor>::New();
  this->CapActor->SetMapper(capMapper);
  this->CapActor->GetProperty()->SetAmbient(0.35);
  this->CapActor->GetProperty()->SetDiffuse(0.65);
  this->CapActor->PickableOff();
  this->CapActor->VisibilityOff();
  this->SurfaceLayer->AddActor(this->CapActor);
  this->MouseObserver->SetCallback(&CfdEndsOverlay::OnMouse);
  this->MouseObserver->SetClientData(this);
  if (vtkRenderWindow* window = this->SurfaceLayer->GetRenderWindow())
  {
    if (vtkRenderWindowInteractor* interactor = window->GetInteractor())
    {
      // Before the cursor overlay (20), the view's picking (10), the ribbon widget and the
      // camera style: a press on a handle is the overlay's alone.
      for (unsigned long event : { vtkCommand::LeftButtonPressEvent,
             vtkCommand::MouseMoveEvent,
             vtkCommand::LeftButtonReleaseEvent })
      {
        interactor->AddObserver(event, this->MouseObserver, 30.0f);
      }
    }
  }
}

CfdEndsOverlay::~CfdEndsOverlay()
{
  if (vtkRenderWindow* window = this->SurfaceLayer->GetRenderWindow())
  {
    if (vtkRenderWindowInteractor* interactor = window->GetInteractor())
    {
      interactor->RemoveObserver(this->MouseObserver);
    }
  }
  this->removeEnds();
  this->removePatches();
  this->SurfaceLayer->RemoveActor(this->CapActor);
}

void CfdEndsOverlay::removeEnds()
{
  for (EndActors& end : this->Ends)
  {
    this->SurfaceLayer->RemoveActor(end.discActor);
    this->SurfaceLayer->RemoveActor(end.rimActor);
    this->TopLayer->RemoveActor(end.handle);
    this->TopLayer->RemoveViewProp(end.text);
  }
  this->Ends.clear();
  this->Dragged = -1;
}

void CfdEndsOverlay::removePatches()
{
  for (auto& text : this->PatchTexts)
  {
    this->TopLayer->RemoveViewProp(text);
  }
  this->PatchTexts.clear();
  this->CapData->Initialize();
  this->CapData->Modified();
  this->CapActor->VisibilityOff();
  this->ShowingPatches = false;
}

void CfdEndsOverlay::clear()
{
  this->removeEnds();
  this->removePatches();
}

void CfdEndsOverlay::setEnds(const std::vector<bender::CenterlineEndPath>& paths)
{
  this->clear();
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(20);
  sphere->SetPhiResolution(12);
  sphere->Update();
  for (std::size_t k = 0; k < paths.size(); ++k)
  {
    EndActors end;
    end.path = paths[k];
    end.distance = std::clamp(end.path.defaultDistance, 0.0, end.path.maximumDistance);
    end.label = QString("end %1").arg(k + 1);
    end.disc = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkPolyDataMapper> discMapper;
    discMapper->SetInputData(end.disc);
    discMapper->ScalarVisibilityOff();
    end.discActor = vtkSmartPointer<vtkActor>::New();
    end.discActor->SetMapper(discMapper);
    end.discActor->GetProperty()->SetOpacity(0.4);
    end.discActor->GetProperty()->BackfaceCullingOff();
    end.discActor->GetProperty()->SetAmbient(0.5);
    end.discActor->GetProperty()->SetDiffuse(0.5);
    end.discActor->PickableOff();
    // The rim: the disc's outline, opaque.
    vtkNew<vtkPolyDataMapper> rimMapper;
    rimMapper->ScalarVisibilityOff();
    end.rimActor = vtkSmartPointer<vtkActor>::New();
    end.rimActor->SetMapper(rimMapper);
    end.rimActor->GetProperty()->SetLineWidth(2.5);
    end.rimActor->GetProperty()->LightingOff();
    end.rimActor->PickableOff();
    vtkNew<vtkPolyDataMapper> handleMapper;
    handleMapper->SetInputConnection(sphere->GetOutputPort());
    handleMapper->ScalarVisibilityOff();
    end.handle = vtkSmartPointer<vtkActor>::New();
    end.handle->SetMapper(handleMapper);
    end.handle->GetProperty()->SetAmbient(0.4);
    end.handle->PickableOff();
    end.text = MakeText(OutletColour);
    this->SurfaceLayer->AddActor(end.discActor);
    this->SurfaceLayer->AddActor(end.rimActor);
    this->TopLayer->AddActor(end.handle);
    this->TopLayer->AddViewProp(end.text);
    this->Ends.push_back(end);
    this->updateEnd(this->Ends.back());
  }
  this->updateVisibility();
}

const bender::CenterlineEndPath& CfdEndsOverlay::path(int end) const
{
  return this->Ends.at(static_cast<std::size_t>(end)).path;
}

void CfdEndsOverlay::setDistance(int end, double distance)
{
  if (end < 0 || end >= this->numberOfEnds() || !std::isfinite(distance))
  {
    return;
  }
  EndActors& e = this->Ends[static_cast<std::size_t>(end)];
  e.distance = std::clamp(distance, 0.0, e.path.maximumDistance);
  this->updateEnd(e);
}

double CfdEndsOverlay::distance(int end) const
{
  return end >= 0 && end < this->numberOfEnds() ? this->Ends[static_cast<std::size_t>(end)].distance
                                                : 0.0;
}

void CfdEndsOverlay::setLabel(int end, const QString& label, bool inlet)
{
  if (end < 0 || end >= this->numberOfEnds())
  {
    return;
  }
  EndActors& e = this->Ends[static_cast<std::size_t>(end)];
  e.label = label;
  e.inlet = inlet;
  this->updateEnd(e);
}

QString CfdEndsOverlay::label(int end) const
{
  return end >= 0 && end < this->numberOfEnds() ? this->Ends[static_cast<std::size_t>(end)].label
                                                : QString();
}

bender::ClipPlane CfdEndsOverlay::plane(int end) const
{
  if (end < 0 || end >= this->numberOfEnds())
  {
    return {};
  }
  const EndActors& e = this->Ends[static_cast<std::size_t>(end)];
  return bender::ClipPlaneAt(e.path, e.distance);
}

vtkPolyData* CfdEndsOverlay::disc(int end) const
{
  return end >= 0 && end < this->numberOfEnds()
    ? this->Ends[static_cast<std::size_t>(end)].disc.GetPointer()
    : nullptr;
}

void CfdEndsOverlay::updateEnd(EndActors& end)
{
  const bender::ClipPlane plane = bender::ClipPlaneAt(end.path, end.distance);
  const double radius = DiscScale * plane.radius;
  const P3 u = Perpendicular(plane.normal);
  const P3 v = Cross(plane.normal, u);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polygon;
  vtkNew<vtkCellArray> outline;
  polygon->InsertNextCell(DiscSides);
  outline->InsertNextCell(DiscSides + 1);
  for (int k = 0; k < DiscSides; ++k)
  {
    const double a = 2.0 * M_PI * k / DiscSides;
    const double c = radius * std::cos(a), s = radius * std::sin(a);
    points->InsertNextPoint(plane.centre[0] + c * u[0] + s * v[0],
      plane.centre[1] + c * u[1] + s * v[1],
      plane.centre[2] + c * u[2] + s * v[2]);
    polygon->InsertCellPoint(k);
    outline->InsertCellPoint(k);
  }
  outline->InsertCellPoint(0);
  end.disc->Initialize();
  end.disc->SetPoints(points);
  end.disc->SetPolys(polygon);
  end.disc->Modified();
  vtkNew<vtkPolyData> rim;
  rim->SetPoints(points);
  rim->SetLines(outline);
  vtkPolyDataMapper::SafeDownCast(end.rimActor->GetMapper())->SetInputData(rim);
  const double* colour = end.inlet ? InletColour : OutletColour;
  end.discActor->GetProperty()->SetColor(colour[0], colour[1], colour[2]);
  end.rimActor->GetProperty()->SetColor(colour[0], colour[1], colour[2]);
  end.handle->GetProperty()->SetColor(
    0.5 + 0.5 * colour[0], 0.5 + 0.5 * colour[1], 0.5 + 0.5 * colour[2]);
  end.handle->SetScale(HandleScale * plane.radius);
  end.handle->SetPosition(plane.centre[0], plane.centre[1], plane.centre[2]);
  end.text->SetInput(
    QString("%1  %2 mm").arg(end.label).arg(end.distance, 0, 'f', 1).toUtf8().constData());
  end.text->GetTextProperty()->SetColor(
    colour[0] * 0.4 + 0.6, colour[1] * 0.4 + 0.6, colour[2] * 0.4 + 0.6);
  PlaceText(end.text, plane.centre, 14.0, 8.0);
}

void CfdEndsOverlay::setPatches(vtkPolyData* surface, const std::vector<bender::CfdEnd>& ends)
{
  this->removeEnds();
  this->removePatches();
  vtkDataArray* ids =
    surface ? surface->GetCellData()->GetArray(bender::kCellEntityIdsArrayName) : nullptr;
  if (!surface || !ids)
  {
    this->updateVisibility();
    return;
  }
  // The caps' triangles, coloured by their end's role.
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->DeepCopy(surface->GetPoints());
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetNumberOfComponents(3);
  colours->SetName("Colors");
  for (vtkIdType c = 0; c < surface->GetNumberOfCells() && c < ids->GetNumberOfTuples(); ++c)
  {
    const int id = static_cast<int>(ids->GetTuple1(c));
    if (id < 2)
    {
      continue;
    }
    bool inlet = false;
    for (const bender::CfdEnd& end : ends)
    {
      inlet = inlet || (end.id == id && end.type == bender::PatchType::Inlet);
    }
    vtkIdType npts;
    const vtkIdType* pts;
    surface->GetCellPoints(c, npts, pts);
    polys->InsertNextCell(npts, pts);
    const double* colour = inlet ? InletColour : OutletColour;
    colours->InsertNextTuple3(255 * colour[0], 255 * colour[1], 255 * colour[2]);
  }
  this->CapData->SetPoints(points);
  this->CapData->SetPolys(polys);
  this->CapData->GetCellData()->SetScalars(colours);
  this->CapData->Modified();
  for (const bender::CfdEnd& end : ends)
  {
    auto text = MakeText(end.type == bender::PatchType::Inlet ? InletColour : OutletColour);
    text->SetInput(end.name.c_str());
    PlaceText(text, end.centre, 10.0, 6.0);
    this->TopLayer->AddViewProp(text);
    this->PatchTexts.push_back(text);
  }
  this->ShowingPatches = true;
  this->updateVisibility();
}

int CfdEndsOverlay::numberOfPatchLabelsShown() const
{
  int shown = 0;
  for (const auto& text : this->PatchTexts)
  {
    shown += text->GetVisibility() ? 1 : 0;
  }
  return shown;
}

std::vector<QString> CfdEndsOverlay::patchLabels() const
{
  std::vector<QString> labels;
  for (const auto& text : this->PatchTexts)
  {
    labels.push_back(QString::fromUtf8(text->GetInput()));
  }
  return labels;
}

int CfdEndsOverlay::numberOfDiscsShown() const
{
  int shown = 0;
  for (const EndActors& end : this->Ends)
  {
    shown += end.discActor->GetVisibility() ? 1 : 0;
  }
  return shown;
}

void CfdEndsOverlay::setVisible(bool visible)
{
  this->Visible = visible;
  if (!visible)
  {
    this->Dragged = -1;
  }
  this->updateVisibility();
}

void CfdEndsOverlay::updateVisibility()
{
  for (EndActors& end : this->Ends)
  {
    for (vtkProp* prop : { static_cast<vtkProp*>(end.discActor),
           static_cast<vtkProp*>(end.rimActor),
           static_cast<vtkProp*>(end.handle),
           static_cast<vtkProp*>(end.text) })
    {
      prop->SetVisibility(this->Visible);
    }
  }
  this->CapActor->SetVisibility(this->Visible && this->ShowingPatches);
  for (auto& text : this->PatchTexts)
  {
    text->SetVisibility(this->Visible);
  }
}

bool CfdEndsOverlay::pathDisplayPosition(int end, double distance, double position[2]) const
{
  if (end < 0 || end >= this->numberOfEnds())
  {
    return false;
  }
  const bender::ClipPlane plane =
    bender::ClipPlaneAt(this->Ends[static_cast<std::size_t>(end)].path, distance);
  vtkRenderer* renderer = this->SurfaceLayer;
  renderer->SetWorldPoint(plane.centre[0], plane.centre[1], plane.centre[2], 1.0);
  renderer->WorldToDisplay();
  const double* d = renderer->GetDisplayPoint();
  position[0] = d[0];
  position[1] = d[1];
  return true;
}

bool CfdEndsOverlay::handleDisplayPosition(int end, double position[2]) const
{
  if (!this->Visible || end < 0 || end >= this->numberOfEnds())
  {
    return false;
  }
  return this->pathDisplayPosition(end, this->distance(end), position);
}

int CfdEndsOverlay::handleAt(int x, int y) const
{
  int best = -1;
  double bestD = std::numeric_limits<double>::infinity();
  for (int k = 0; k < this->numberOfEnds(); ++k)
  {
    double p[2];
    if (!this->handleDisplayPosition(k, p))
    {
      continue;
    }
    // The handle's size on the screen, at least PickPixels.
    const bender::ClipPlane plane = this->plane(k);
    double tolerance = PickPixels;
    vtkRenderer* renderer = this->SurfaceLayer;
    const P3 u = Perpendicular(plane.normal);
    const double r = HandleScale * plane.radius;
    renderer->SetWorldPoint(
      plane.centre[0] + r * u[0], plane.centre[1] + r * u[1], plane.centre[2] + r * u[2], 1.0);
    renderer->WorldToDisplay();
    const double* rim = renderer->GetDisplayPoint();
    tolerance = std::max(tolerance, std::hypot(rim[0] - p[0], rim[1] - p[1]));
    const double d = std::hypot(x - p[0], y - p[1]);
    if (d <= tolerance && d < bestD)
    {
      bestD = d;
      best = k;
    }
  }
  return best;
}

double CfdEndsOverlay::distanceAt(int end, int x, int y) const
{
  // The centerline point whose screen position is nearest the mouse (over the path's range).
  const EndActors& e = this->Ends[static_cast<std::size_t>(end)];
  const bender::CenterlineEndPath& path = e.path;
  vtkRenderer* renderer = this->SurfaceLayer;
  std::vector<std::array<double, 2>> screen;
  std::size_t count = 0;
  while (
    count < path.points.size() && (count == 0 || path.arcLengths[count - 1] < path.maximumDistance))
  {
    ++count;
  }
  for (std::size_t i = 0; i < count; ++i)
  {
    renderer->SetWorldPoint(path.points[i][0], path.points[i][1], path.points[i][2], 1.0);
    renderer->WorldToDisplay();
    const double* d = renderer->GetDisplayPoint();
    screen.push_back({ { d[0], d[1] } });
  }
  double best = e.distance, bestD = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < screen.size(); ++i)
  {
    const double dx = screen[i + 1][0] - screen[i][0], dy = screen[i + 1][1] - screen[i][1];
    const double dd = dx * dx + dy * dy;
    const double t =
      dd > 0 ? std::clamp(((x - screen[i][0]) * dx + (y - screen[i][1]) * dy) / dd, 0.0, 1.0) : 0.0;
    const double d = std::hypot(screen[i][0] + t * dx - x, screen[i][1] + t * dy - y);
    if (d < bestD)
    {
      bestD = d;
      best = path.arcLengths[i] + t * (path.arcLengths[i + 1] - path.arcLengths[i]);
    }
  }
  return std::clamp(best, 0.0, path.maximumDistance);
}

void CfdEndsOverlay::OnMouse(vtkObject* caller, unsigned long event, void* clientData, void*)
{
  (void)caller;
  static_cast<CfdEndsOverlay*>(clientData)->mouse(event);
}

void CfdEndsOverlay::mouse(unsigned long event)
{
  vtkRenderWindow* window = this->SurfaceLayer->GetRenderWindow();
  vtkRenderWindowInteractor* interactor = window ? window->GetInteractor() : nullptr;
  if (!interactor || !this->Visible || this->ShowingPatches || this->Ends.empty())
  {
    return;
  }
  const int* position = interactor->GetEventPosition();
  if (event == vtkCommand::LeftButtonPressEvent)
  {
    // Shift and Ctrl drags are the camera's (pan, spin) and Shift+click the cursor's.
    if (interactor->GetShiftKey() || interactor->GetControlKey())
    {
      return;
    }
    this->Dragged = this->handleAt(position[0], position[1]);
    if (this->Dragged >= 0)
    {
      this->MouseObserver->SetAbortFlag(1);
    }
    return;
  }
  if (this->Dragged < 0)
  {
    return;
  }
  this->MouseObserver->SetAbortFlag(1);
  const int end = this->Dragged;
  if (event == vtkCommand::MouseMoveEvent)
  {
    const double s = this->distanceAt(end, position[0], position[1]);
    if (s != this->distance(end))
    {
      this->setDistance(end, s);
      emit this->distanceChanged(end, this->distance(end));
      this->render();
    }
  }
  else if (event == vtkCommand::LeftButtonReleaseEvent)
  {
    this->Dragged = -1;
    emit this->dragFinished(end);
    this->render();
  }
}

void CfdEndsOverlay::render()
{
  if (vtkRenderWindow* window = this->SurfaceLayer->GetRenderWindow())
  {
    window->Render();
  }
}
