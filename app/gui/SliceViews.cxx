#include "SliceViews.h"

#include "BenderView.h"
#include "CursorOverlay.h"

#include <QComboBox>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QStringList>
#include <QVTKOpenGLNativeWidget.h>

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCornerAnnotation.h>
#include <vtkDataArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkImageData.h>
#include <vtkImageProperty.h>
#include <vtkImageResliceMapper.h>
#include <vtkImageSlice.h>
#include <vtkInteractorStyleImage.h>
#include <vtkLookupTable.h>
#include <vtkMatrix3x3.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <vector>

namespace
{
// Each view's colour (its title, its trace in the other views, its plane in the 3D view):
// axial red, coronal green, sagittal yellow.
const unsigned char ViewColours[3][3] = { { 242, 97, 89 }, { 115, 217, 102 }, { 242, 217, 77 } };
// The LPS axis along each view's normal: axial z (S), coronal y (P), sagittal x (L).
int AxisOf(int view)
{
  return view == SliceViews::Axial ? 2 : (view == SliceViews::Coronal ? 1 : 0);
}

/// The slice views' mouse: a left click or drag moves the cursor (through `MoveCursor`, with
/// the event's display position), Shift+left drag sets the window/level (the image style's
/// plain left drag); the rest is vtkInteractorStyleImage's (right zoom, middle pan).
class SliceStyle : public vtkInteractorStyleImage
{
public:
  static SliceStyle* New();
  vtkTypeMacro(SliceStyle, vtkInteractorStyleImage);

  std::function<void(int, int)> MoveCursor;

  void OnLeftButtonDown() override
  {
    vtkRenderWindowInteractor* rwi = this->Interactor;
    if (rwi->GetShiftKey() && !rwi->GetControlKey())
    {
      // The image style's window/level is its left drag without modifiers.
      rwi->SetShiftKey(0);
      this->Superclass::OnLeftButtonDown();
      rwi->SetShiftKey(1);
      return;
    }
    const int* at = rwi->GetEventPosition();
    this->FindPokedRenderer(at[0], at[1]);
    if (!this->CurrentRenderer)
    {
      return;
    }
    this->Dragging = true;
    this->GrabFocus(this->EventCallbackCommand);
    if (this->MoveCursor)
    {
      this->MoveCursor(at[0], at[1]);
    }
  }
  void OnMouseMove() override
  {
    if (!this->Dragging)
    {
      this->Superclass::OnMouseMove();
      return;
    }
    const int* at = this->Interactor->GetEventPosition();
    if (this->MoveCursor)
    {
      this->MoveCursor(at[0], at[1]);
    }
  }
  void OnLeftButtonUp() override
  {
    if (!this->Dragging)
    {
      this->Superclass::OnLeftButtonUp();
      return;
    }
    this->Dragging = false;
    this->ReleaseFocus();
  }

private:
  bool Dragging = false;
};
vtkStandardNewMacro(SliceStyle);

// The patient direction a vector points to most (LPS: +x left, +y posterior, +z superior).
const char* Letter(const double v[3])
{
  int axis = 0;
  for (int i = 1; i < 3; ++i)
  {
    if (std::abs(v[i]) > std::abs(v[axis]))
    {
      axis = i;
    }
  }
  static const char* const plus[3] = { "L", "P", "S" };
  static const char* const minus[3] = { "R", "A", "I" };
  return v[axis] >= 0 ? plus[axis] : minus[axis];
}

// The volume's grid without its placement (origin 0, identity direction), sharing the scalars:
// the placement goes into the slice's matrix, which every image mapper honours.
vtkSmartPointer<vtkImageData> Unplaced(vtkImageData* image)
{
  auto grid = vtkSmartPointer<vtkImageData>::New();
  grid->SetDimensions(image->GetDimensions());
  grid->SetSpacing(image->GetSpacing());
  grid->SetOrigin(0, 0, 0);
  grid->GetPointData()->SetScalars(image->GetPointData()->GetScalars());
  return grid;
}

// Index-space mm (spacing applied) to LPS: origin + direction * x.
vtkSmartPointer<vtkMatrix4x4> Placement(vtkImageData* image)
{
  auto matrix = vtkSmartPointer<vtkMatrix4x4>::New();
  vtkMatrix3x3* direction = image->GetDirectionMatrix();
  const double* origin = image->GetOrigin();
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      matrix->SetElement(r, c, direction->GetElement(r, c));
    }
    matrix->SetElement(r, 3, origin[r]);
  }
  return matrix;
}

// The 0.5 and 99.5 percentiles of the scalars (on a sample of at most ~1M values).
void RobustRange(vtkDataArray* scalars, double range[2])
{
  scalars->GetRange(range, 0);
  const vtkIdType n = scalars->GetNumberOfTuples();
  if (n < 2)
  {
    return;
  }
  const vtkIdType stride = std::max<vtkIdType>(1, n / 1000000);
  std::vector<double> sample;
  sample.reserve(static_cast<std::size_t>(n / stride + 1));
  for (vtkIdType i = 0; i < n; i += stride)
  {
    const double v = scalars->GetComponent(i, 0);
    if (std::isfinite(v))
    {
      sample.push_back(v);
    }
  }
  if (sample.size() < 2)
  {
    return;
  }
  auto at = [&sample](double q)
  {
    const std::size_t k = static_cast<std::size_t>(q * static_cast<double>(sample.size() - 1));
    std::nth_element(sample.begin(), sample.begin() + static_cast<std::ptrdiff_t>(k), sample.end());
    return sample[k];
  };
  const double low = at(0.005);
  const double high = at(0.995);
  if (high > low)
  {
    range[0] = low;
    range[1] = high;
  }
}
}

struct SliceViews::View
{
  SliceViews* owner = nullptr;
  int index = 0;
  QVTKOpenGLNativeWidget* widget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkImageResliceMapper> mapper;
  vtkNew<vtkImageSlice> slice;
  vtkNew<vtkImageResliceMapper> overlayMapper;
  vtkNew<vtkImageSlice> overlay;
  vtkNew<SliceStyle> style;
  vtkNew<vtkCornerAnnotation> annotation;
  vtkNew<vtkPolyData> crosshairData;
  vtkNew<vtkPolyDataMapper> crosshairMapper;
  vtkNew<vtkActor> crosshair;
  vtkNew<vtkCallbackCommand> inputObserver;
  vtkNew<vtkCallbackCommand> renderObserver;
  double viewDirection[3] = { 0, 0, 1 };
  double viewUp[3] = { 0, 1, 0 };
  int fittedSize[2] = { 0, 0 };

  void fit();
};

namespace
{
void OnInput(vtkObject* caller, unsigned long event, void* clientData, void*)
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
}

// Zoomed to show the whole volume's section in this view, centred; the slice stays.
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

SliceViews::SliceViews(QWidget* parent)
  : QWidget(parent)
{
  auto* layout = new QGridLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  // LPS: axial seen from the feet, coronal from the front, sagittal from the left.
  const double directions[3][3] = { { 0, 0, 1 }, { 0, 1, 0 }, { -1, 0, 0 } };
  const double ups[3][3] = { { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, 1 } };
  const char* names[3] = { "Axial", "Coronal", "Sagittal" };
  vtkNew<vtkLookupTable> maskColours;
  maskColours->SetNumberOfTableValues(2);
  maskColours->SetTableRange(0, 1);
  maskColours->SetTableValue(0, 0, 0, 0, 0);
  maskColours->SetTableValue(1, 1, 0.2, 0.2, 0.45);
  maskColours->Build();
  for (int i = 0; i < 3; ++i)
  {
    auto* view = new View;
    this->Views[i] = view;
    view->owner = this;
    view->index = i;
    view->widget = new QVTKOpenGLNativeWidget(this);
    view->widget->setObjectName(QString("slice%1").arg(names[i]));
    view->widget->setToolTip(
      QString("%1 slice: a left click or drag moves the cursor (the other slices follow it); "
              "the mouse wheel or Up/Down moves the slice; Shift+left drag sets the "
              "window/level, right drag zooms, middle drag pans, R frames the slice again")
        .arg(names[i]));
    view->widget->setRenderWindow(view->window);
    view->window->AddRenderer(view->renderer);
    view->renderer->SetBackground(0.05, 0.05, 0.07);
    view->mapper->SliceFacesCameraOn();
    view->mapper->SliceAtFocalPointOn();
    view->slice->SetMapper(view->mapper);
    view->overlayMapper->SliceFacesCameraOn();
    view->overlayMapper->SliceAtFocalPointOn();
    view->overlay->SetMapper(view->overlayMapper);
    view->overlay->GetProperty()->SetLookupTable(maskColours);
    view->overlay->GetProperty()->SetInterpolationTypeToNearest();
    view->overlay->GetProperty()->UseLookupTableScalarRangeOn();
    view->overlay->PickableOff();
    view->style->SetInteractionModeToImageSlicing();
    // The window/level drag sets the volume's slice (the first image), not the mask's (the
    // style's default, the topmost image, is the mask overlay).
    view->style->SetCurrentImageNumber(0);
    view->style->MoveCursor = [this, i](int x, int y)
    {
      double position[3];
      this->displayToCursor(i, x, y, position);
      this->setCursor(position);
    };
    view->window->GetInteractor()->SetInteractorStyle(view->style);
    view->crosshairMapper->SetInputData(view->crosshairData);
    view->crosshairMapper->SetScalarModeToUseCellData();
    view->crosshair->SetMapper(view->crosshairMapper);
    view->crosshair->GetProperty()->SetLineWidth(1.5);
    view->crosshair->GetProperty()->LightingOff();
    view->crosshair->PickableOff();
    view->inputObserver->SetCallback(&OnInput);
    view->inputObserver->SetClientData(view);
    for (unsigned long event : { vtkCommand::MouseWheelForwardEvent,
           vtkCommand::MouseWheelBackwardEvent,
           vtkCommand::KeyPressEvent,
           vtkCommand::CharEvent })
    {
      view->window->GetInteractor()->AddObserver(event, view->inputObserver, 1.0f);
    }
    view->renderObserver->SetCallback(&SliceViews::BeforeRender);
    view->renderObserver->SetClientData(view);
    view->renderer->AddObserver(vtkCommand::StartEvent, view->renderObserver);
    view->annotation->SetMaximumFontSize(16);
    view->annotation->SetLinearFontScaleFactor(2);
    view->annotation->SetNonlinearFontScaleFactor(1);
    view->annotation->GetTextProperty()->SetColor(0.95, 0.85, 0.35);
    view->annotation->GetTextProperty()->ShadowOn();
    std::copy(directions[i], directions[i] + 3, view->viewDirection);
    std::copy(ups[i], ups[i] + 3, view->viewUp);
    auto* label = new QLabel(names[i], this);
    label->setStyleSheet(QString("color: rgb(%1, %2, %3); font-weight: bold;")
                           .arg(ViewColours[i][0])
                           .arg(ViewColours[i][1])
                           .arg(ViewColours[i][2]));
    layout->addWidget(label, 0, i);
    layout->addWidget(view->widget, 1, i);
  }
  layout->setRowStretch(1, 1);
  auto* row = new QHBoxLayout;
  this->CursorLabel = new QLabel("Cursor: no volume", this);
  this->CursorLabel->setObjectName("sliceCursor");
  this->CursorLabel->setToolTip("The cursor shared by the slice views and the 3D view (LPS "
                                "model coordinates, mm), the intensity of the voxel under it "
                                "and whether it is segmented");
  this->CursorLabel->setTextInteractionFlags(Qt::TextSelectableByMouse);
  row->addWidget(this->CursorLabel, 1);
  row->addWidget(new QLabel("In the 3D view:", this));
  this->CursorStyle = new QComboBox(this);
  this->CursorStyle->setObjectName("sliceCursorStyle");
  this->CursorStyle->addItem("no cursor");
  this->CursorStyle->addItem("crosshair");
  this->CursorStyle->addItem("crosshair and slice planes");
  this->CursorStyle->setCurrentIndex(CursorOverlay::Crosshair);
  this->CursorStyle->setToolTip("How the cursor is drawn in the 3D view; there, Shift+click on "
                                "the surface moves the cursor and the slices to that point");
  row->addWidget(this->CursorStyle);
  layout->addLayout(row, 2, 0, 1, 3);
  connect(this->CursorStyle,
    QOverload<int>::of(&QComboBox::currentIndexChanged),
    this,
    [this](int index)
    {
      if (!this->Overlay)
        return;
      this->Overlay->setStyle(static_cast<CursorOverlay::Style>(index));
      if (this->LinkedView)
        this->LinkedView->render();
    });
}

void SliceViews::linkView(BenderView* view)
{
  if (this->Overlay || !view)
  {
    return;
  }
  this->LinkedView = view;
  this->Overlay =
    new CursorOverlay(view->ribbonRenderer(), view->renderer(), view->surfaceActor(), this);
  this->Overlay->setBusy([view]() { return view->isPicking(); });
  this->Overlay->setStyle(static_cast<CursorOverlay::Style>(this->CursorStyle->currentIndex()));
  const double none[6] = { 0, -1, 0, -1, 0, -1 };
  this->Overlay->setBounds(this->Volume ? this->Bounds : none);
  this->Overlay->setPosition(this->Cursor);
  connect(this->Overlay,
    &CursorOverlay::picked,
    this,
    [this](double x, double y, double z)
    {
      const double position[3] = { x, y, z };
      this->setCursor(position);
    });
}

SliceViews::~SliceViews()
{
  for (View* view : this->Views)
  {
    delete view;
  }
}

void SliceViews::BeforeRender(vtkObject*, unsigned long, void* clientData, void*)
{
  auto* view = static_cast<View*>(clientData);
  const int* size = view->renderer->GetSize();
  if (size[0] != view->fittedSize[0] || size[1] != view->fittedSize[1])
  {
    view->fit(); // first frame, or the pane was resized
  }
  view->owner->updateAnnotation(view->index);
}

void SliceViews::volumeBounds(double bounds[6]) const
{
  std::copy(this->Bounds, this->Bounds + 6, bounds);
}

void SliceViews::setVolume(vtkImageData* volume, vtkImageData* mask)
{
  const double previous[6] = { this->Bounds[0],
    this->Bounds[1],
    this->Bounds[2],
    this->Bounds[3],
    this->Bounds[4],
    this->Bounds[5] };
  const bool hadVolume = this->Volume != nullptr;
  this->Volume = volume;
  this->Mask = mask;
  if (volume)
  {
    // The box of the voxels' outer faces in LPS: the 8 corners through the placement.
    int dims[3];
    volume->GetDimensions(dims);
    const double* spacing = volume->GetSpacing();
    vtkSmartPointer<vtkMatrix4x4> placement = Placement(volume);
    for (int axis = 0; axis < 3; ++axis)
    {
      this->Bounds[2 * axis] = VTK_DOUBLE_MAX;
      this->Bounds[2 * axis + 1] = VTK_DOUBLE_MIN;
    }
    for (int corner = 0; corner < 8; ++corner)
    {
      double local[4] = { 0, 0, 0, 1 };
      for (int axis = 0; axis < 3; ++axis)
      {
        const double half = 0.5 * spacing[axis];
        local[axis] = (corner >> axis) & 1 ? (dims[axis] - 1) * spacing[axis] + half : -half;
      }
      double world[4];
      placement->MultiplyPoint(local, world);
      for (int axis = 0; axis < 3; ++axis)
      {
        this->Bounds[2 * axis] = std::min(this->Bounds[2 * axis], world[axis]);
        this->Bounds[2 * axis + 1] = std::max(this->Bounds[2 * axis + 1], world[axis]);
      }
    }
    this->StepLength = std::max(1e-6, *std::min_element(spacing, spacing + 3));
    if (!hadVolume || !std::equal(previous, previous + 6, this->Bounds))
    {
      for (int axis = 0; axis < 3; ++axis)
      {
        this->Cursor[axis] = 0.5 * (this->Bounds[2 * axis] + this->Bounds[2 * axis + 1]);
      }
    }
  }
  for (View* view : this->Views)
  {
    view->renderer->RemoveAllViewProps();
    view->fittedSize[0] = view->fittedSize[1] = 0;
    if (!volume)
    {
      continue;
    }
    view->mapper->SetInputData(Unplaced(volume));
    view->slice->SetUserMatrix(Placement(volume));
    double range[2];
    RobustRange(volume->GetPointData()->GetScalars(), range);
    view->slice->GetProperty()->SetColorWindow(std::max(range[1] - range[0], 1e-6));
    view->slice->GetProperty()->SetColorLevel(0.5 * (range[0] + range[1]));
    view->renderer->AddViewProp(view->slice);
    if (mask)
    {
      view->overlayMapper->SetInputData(Unplaced(mask));
      view->overlay->SetUserMatrix(Placement(mask));
      view->renderer->AddViewProp(view->overlay);
    }
    view->renderer->AddViewProp(view->crosshair);
    view->renderer->AddViewProp(view->annotation);
    // Framed on the box's centre, sliced through the cursor.
    double centre[3] = { 0.5 * (this->Bounds[0] + this->Bounds[1]),
      0.5 * (this->Bounds[2] + this->Bounds[3]),
      0.5 * (this->Bounds[4] + this->Bounds[5]) };
    centre[AxisOf(view->index)] = this->Cursor[AxisOf(view->index)];
    vtkCamera* camera = view->renderer->GetActiveCamera();
    camera->ParallelProjectionOn();
    const double distance = 2.0 *
        (this->Bounds[1] - this->Bounds[0] + this->Bounds[3] - this->Bounds[2] + this->Bounds[5] -
          this->Bounds[4]) +
      1.0;
    camera->SetFocalPoint(centre);
    camera->SetPosition(centre[0] - distance * view->viewDirection[0],
      centre[1] - distance * view->viewDirection[1],
      centre[2] - distance * view->viewDirection[2]);
    camera->SetViewUp(view->viewUp);
    camera->SetClippingRange(0.5 * distance, 1.5 * distance);
    view->fit();
  }
  if (this->Overlay)
  {
    const double none[6] = { 0, -1, 0, -1, 0, -1 };
    this->Overlay->setBounds(volume ? this->Bounds : none);
    this->Overlay->setPosition(this->Cursor);
  }
  this->updateCrosshairs();
  this->render();
  if (this->LinkedView)
  {
    this->LinkedView->render();
  }
}

vtkRenderer* SliceViews::renderer(int view) const
{
  return this->Views[std::max(0, std::min(2, view))]->renderer;
}

vtkImageSlice* SliceViews::slice(int view) const
{
  return this->Views[std::max(0, std::min(2, view))]->slice;
}

QVTKOpenGLNativeWidget* SliceViews::viewWidget(int view) const
{
  return this->Views[std::max(0, std::min(2, view))]->widget;
}

double SliceViews::slicePosition(int view) const
{
  const View* v = this->Views[std::max(0, std::min(2, view))];
  const double* focal = v->renderer->GetActiveCamera()->GetFocalPoint();
  return focal[AxisOf(view)];
}

void SliceViews::moveSlice(int view, int steps)
{
  if (!this->Volume)
  {
    return;
  }
  const View* v = this->Views[std::max(0, std::min(2, view))];
  const int axis = AxisOf(v->index);
  // Forward (wheel up) goes towards the viewer's side: S, A, L.
  const double step = -steps * this->StepLength;
  double position[3] = { this->Cursor[0], this->Cursor[1], this->Cursor[2] };
  position[axis] += step * v->viewDirection[axis];
  this->setCursor(position);
}

void SliceViews::resetView(int view)
{
  if (!this->Volume)
  {
    return;
  }
  View* v = this->Views[std::max(0, std::min(2, view))];
  const int axis = AxisOf(v->index);
  double centre[3];
  for (int a = 0; a < 3; ++a)
  {
    centre[a] = a == axis ? this->Cursor[a] : 0.5 * (this->Bounds[2 * a] + this->Bounds[2 * a + 1]);
  }
  vtkCamera* camera = v->renderer->GetActiveCamera();
  const double distance = camera->GetDistance();
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0] - distance * v->viewDirection[0],
    centre[1] - distance * v->viewDirection[1],
    centre[2] - distance * v->viewDirection[2]);
  camera->SetViewUp(v->viewUp);
  v->fit();
  v->window->Render();
}

void SliceViews::setCursor(const double position[3])
{
  if (!this->Volume)
  {
    return;
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    const double p = std::isfinite(position[axis]) ? position[axis] : this->Cursor[axis];
    this->Cursor[axis] = std::min(this->Bounds[2 * axis + 1], std::max(this->Bounds[2 * axis], p));
  }
  // Each view's slice through the cursor: its camera slides along its normal (the pan and the
  // zoom stay).
  for (View* v : this->Views)
  {
    const int axis = AxisOf(v->index);
    vtkCamera* camera = v->renderer->GetActiveCamera();
    double focal[3], eye[3];
    camera->GetFocalPoint(focal);
    camera->GetPosition(eye);
    const double shift = this->Cursor[axis] - focal[axis];
    focal[axis] += shift;
    eye[axis] += shift;
    camera->SetFocalPoint(focal);
    camera->SetPosition(eye);
  }
  if (this->Overlay)
  {
    this->Overlay->setPosition(this->Cursor);
  }
  this->updateCrosshairs();
  this->render();
  if (this->LinkedView)
  {
    this->LinkedView->render();
  }
  emit this->cursorMoved(this->Cursor[0], this->Cursor[1], this->Cursor[2]);
}

vtkImageData* SliceViews::volume() const
{
  return this->Volume;
}

void SliceViews::cursor(double position[3]) const
{
  std::copy(this->Cursor, this->Cursor + 3, position);
}

void SliceViews::displayToCursor(int view, int x, int y, double position[3]) const
{
  const View* v = this->Views[std::max(0, std::min(2, view))];
  // A parallel projection: the display point on the focal plane is the point in the slice.
  vtkRenderer* renderer = v->renderer;
  renderer->SetDisplayPoint(x, y, 0.5);
  renderer->DisplayToWorld();
  double world[4];
  renderer->GetWorldPoint(world);
  const double w = world[3] != 0.0 ? world[3] : 1.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    position[axis] = world[axis] / w;
  }
  position[AxisOf(v->index)] = this->Cursor[AxisOf(v->index)];
}

namespace
{
// The voxel nearest `point` (LPS), false outside the image's extent.
bool NearestVoxel(vtkImageData* image, const double point[3], int ijk[3])
{
  if (!image)
  {
    return false;
  }
  double continuous[3];
  image->TransformPhysicalPointToContinuousIndex(point, continuous);
  const int* extent = image->GetExtent();
  for (int axis = 0; axis < 3; ++axis)
  {
    if (!std::isfinite(continuous[axis]))
    {
      return false;
    }
    ijk[axis] = static_cast<int>(std::lround(continuous[axis]));
    if (ijk[axis] < extent[2 * axis] || ijk[axis] > extent[2 * axis + 1])
    {
      return false;
    }
  }
  return true;
}
}

bool SliceViews::cursorValue(double& value) const
{
  int ijk[3];
  if (!NearestVoxel(this->Volume, this->Cursor, ijk) || !this->Volume->GetPointData()->GetScalars())
  {
    return false;
  }
  value = this->Volume->GetScalarComponentAsDouble(ijk[0], ijk[1], ijk[2], 0);
  return true;
}

bool SliceViews::cursorSegmented() const
{
  int ijk[3];
  if (!NearestVoxel(this->Mask, this->Cursor, ijk) || !this->Mask->GetPointData()->GetScalars())
  {
    return false;
  }
  return this->Mask->GetScalarComponentAsDouble(ijk[0], ijk[1], ijk[2], 0) > 0.0;
}

int SliceViews::sliceIndex(int view) const
{
  if (!this->Volume)
  {
    return -1;
  }
  // The volume axis closest to the view's normal: the largest entry of the direction matrix's
  // row for the view's LPS axis.
  const int axis = AxisOf(std::max(0, std::min(2, view)));
  vtkMatrix3x3* direction = this->Volume->GetDirectionMatrix();
  int along = 0;
  for (int c = 1; c < 3; ++c)
  {
    if (std::abs(direction->GetElement(axis, c)) > std::abs(direction->GetElement(axis, along)))
    {
      along = c;
    }
  }
  double continuous[3];
  this->Volume->TransformPhysicalPointToContinuousIndex(this->Cursor, continuous);
  const int* extent = this->Volume->GetExtent();
  const long index = std::lround(continuous[along]);
  return static_cast<int>(
    std::min<long>(extent[2 * along + 1], std::max<long>(extent[2 * along], index)));
}

QString SliceViews::cursorText() const
{
  if (!this->Volume)
  {
    return "Cursor: no volume";
  }
  static const char* const plus[3] = { "L", "P", "S" };
  static const char* const minus[3] = { "R", "A", "I" };
  QStringList parts;
  for (int axis = 0; axis < 3; ++axis)
  {
    parts << QString("%1 %2")
               .arg(this->Cursor[axis] >= 0 ? plus[axis] : minus[axis])
               .arg(std::abs(this->Cursor[axis]), 0, 'f', 1);
  }
  QString text = QString("Cursor %1 mm").arg(parts.join(", "));
  double value = 0.0;
  if (this->cursorValue(value))
  {
    text += QString(": %1").arg(value, 0, 'g', 5);
    if (this->cursorSegmented())
    {
      text += " (segmented)";
    }
  }
  return text;
}

vtkPolyData* SliceViews::crosshair(int view) const
{
  return this->Views[std::max(0, std::min(2, view))]->crosshairData;
}

void SliceViews::updateCrosshairs()
{
  if (this->CursorLabel)
  {
    this->CursorLabel->setText(this->cursorText());
  }
  if (!this->Volume)
  {
    return;
  }
  for (View* v : this->Views)
  {
    // In view v, the slice of view w is the line where w's axis is at the cursor, running
    // along the third axis over the box; drawn half a voxel in front of the slice.
    const int normal = AxisOf(v->index);
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    vtkNew<vtkCellArray> lines;
    vtkNew<vtkUnsignedCharArray> colours;
    colours->SetName("Colors");
    colours->SetNumberOfComponents(3);
    for (int w = 0; w < 3; ++w)
    {
      if (w == v->index)
      {
        continue;
      }
      const int fixed = AxisOf(w);
      const int running = 3 - normal - fixed;
      double a[3], b[3];
      for (int axis = 0; axis < 3; ++axis)
      {
        a[axis] = b[axis] = this->Cursor[axis] - 0.5 * this->StepLength * v->viewDirection[axis];
      }
      a[running] = this->Bounds[2 * running];
      b[running] = this->Bounds[2 * running + 1];
      const vtkIdType ids[2] = { points->InsertNextPoint(a), points->InsertNextPoint(b) };
      lines->InsertNextCell(2, ids);
      colours->InsertNextTypedTuple(ViewColours[w]);
    }
    v->crosshairData->SetPoints(points);
    v->crosshairData->SetLines(lines);
    v->crosshairData->GetCellData()->SetScalars(colours);
    v->crosshairData->Modified();
  }
}

QString SliceViews::positionText(int view) const
{
  const double position = this->slicePosition(view);
  const int axis = AxisOf(view);
  double direction[3] = { 0, 0, 0 };
  direction[axis] = position >= 0 ? 1.0 : -1.0;
  return QString("%1 %2 mm").arg(Letter(direction)).arg(std::abs(position), 0, 'f', 1);
}

QStringList SliceViews::edgeLetters(int view) const
{
  const View* v = this->Views[std::max(0, std::min(2, view))];
  const double* d = v->viewDirection;
  const double* u = v->viewUp;
  const double r[3] = {
    d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2], d[0] * u[1] - d[1] * u[0]
  };
  const double down[3] = { -u[0], -u[1], -u[2] };
  const double left[3] = { -r[0], -r[1], -r[2] };
  return { Letter(u), Letter(down), Letter(left), Letter(r) };
}

void SliceViews::updateAnnotation(int view)
{
  View* v = this->Views[view];
  if (!this->Volume)
  {
    return;
  }
  const QStringList letters = this->edgeLetters(view);
  v->annotation->SetText(vtkCornerAnnotation::UpperEdge, letters[0].toUtf8().constData());
  v->annotation->SetText(vtkCornerAnnotation::LowerEdge, letters[1].toUtf8().constData());
  v->annotation->SetText(vtkCornerAnnotation::LeftEdge, letters[2].toUtf8().constData());
  v->annotation->SetText(vtkCornerAnnotation::RightEdge, letters[3].toUtf8().constData());
  v->annotation->SetText(
    vtkCornerAnnotation::UpperLeft, this->positionText(view).toUtf8().constData());
}

void SliceViews::render()
{
  for (View* view : this->Views)
  {
    view->window->Render();
  }
}
