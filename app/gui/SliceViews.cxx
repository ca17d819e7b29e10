#include "SliceViews.h"

#include <QGridLayout>
#include <QLabel>
#include <QStringList>
#include <QVTKOpenGLNativeWidget.h>

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
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
#include <vtkPointData.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

namespace
{
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
  vtkNew<vtkInteractorStyleImage> style;
  vtkNew<vtkCornerAnnotation> annotation;
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
    view->widget->setToolTip(QString("%1 slice: mouse wheel or Up/Down moves the slice, left "
                                     "drag sets the window/level, right drag zooms")
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
    view->style->SetInteractionModeToImageSlicing();
    view->window->GetInteractor()->SetInteractorStyle(view->style);
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
    layout->addWidget(label, 0, i);
    layout->addWidget(view->widget, 1, i);
  }
  layout->setRowStretch(1, 1);
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
    view->renderer->AddViewProp(view->annotation);
    const double centre[3] = { 0.5 * (this->Bounds[0] + this->Bounds[1]),
      0.5 * (this->Bounds[2] + this->Bounds[3]),
      0.5 * (this->Bounds[4] + this->Bounds[5]) };
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
  this->render();
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
  const int axis = view == Axial ? 2 : (view == Coronal ? 1 : 0);
  return focal[axis];
}

void SliceViews::moveSlice(int view, int steps)
{
  if (!this->Volume)
  {
    return;
  }
  View* v = this->Views[std::max(0, std::min(2, view))];
  vtkCamera* camera = v->renderer->GetActiveCamera();
  const int axis = view == Axial ? 2 : (view == Coronal ? 1 : 0);
  // Forward (wheel up) goes towards the viewer's side: S, A, L.
  double focal[3], position[3];
  camera->GetFocalPoint(focal);
  camera->GetPosition(position);
  const double step = -steps * this->StepLength;
  const double target = std::min(this->Bounds[2 * axis + 1],
    std::max(this->Bounds[2 * axis], focal[axis] + step * v->viewDirection[axis]));
  const double shift = target - focal[axis];
  focal[axis] += shift;
  position[axis] += shift;
  camera->SetFocalPoint(focal);
  camera->SetPosition(position);
  v->window->Render();
}

QString SliceViews::positionText(int view) const
{
  const double position = this->slicePosition(view);
  const int axis = view == Axial ? 2 : (view == Coronal ? 1 : 0);
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
