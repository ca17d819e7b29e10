#include "SliceViews.h"

#include <QGridLayout>
#include <QLabel>
#include <QVTKOpenGLNativeWidget.h>

#include <vtkCamera.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkImageData.h>
#include <vtkImageProperty.h>
#include <vtkImageResliceMapper.h>
#include <vtkImageSlice.h>
#include <vtkInteractorStyleImage.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

struct SliceViews::View
{
  QVTKOpenGLNativeWidget* widget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkImageResliceMapper> mapper;
  vtkNew<vtkImageSlice> slice;
  vtkNew<vtkImageResliceMapper> overlayMapper;
  vtkNew<vtkImageSlice> overlay;
  vtkNew<vtkInteractorStyleImage> style;
  double viewDirection[3] = { 0, 0, 1 };
  double viewUp[3] = { 0, 1, 0 };
};

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
    view->widget = new QVTKOpenGLNativeWidget(this);
    view->widget->setObjectName(QString("slice%1").arg(names[i]));
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

void SliceViews::setVolume(vtkImageData* volume, vtkImageData* mask)
{
  this->Volume = volume;
  this->Mask = mask;
  for (View* view : this->Views)
  {
    view->renderer->RemoveAllViewProps();
    if (!volume)
    {
      continue;
    }
    view->mapper->SetInputData(volume);
    double range[2];
    volume->GetScalarRange(range);
    view->slice->GetProperty()->SetColorWindow(range[1] - range[0]);
    view->slice->GetProperty()->SetColorLevel(0.5 * (range[0] + range[1]));
    view->renderer->AddViewProp(view->slice);
    if (mask)
    {
      view->overlayMapper->SetInputData(mask);
      view->renderer->AddViewProp(view->overlay);
    }
    double bounds[6];
    volume->GetBounds(bounds);
    const double centre[3] = {
      0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5])
    };
    vtkCamera* camera = view->renderer->GetActiveCamera();
    camera->ParallelProjectionOn();
    camera->SetFocalPoint(centre);
    camera->SetPosition(centre[0] - 500 * view->viewDirection[0],
      centre[1] - 500 * view->viewDirection[1],
      centre[2] - 500 * view->viewDirection[2]);
    camera->SetViewUp(view->viewUp);
    view->renderer->ResetCamera();
  }
  this->render();
}

void SliceViews::render()
{
  for (View* view : this->Views)
  {
    view->window->Render();
  }
}
