#include "BenderView.h"

#include "vtkBenderRibbonWidget.h"

#include <vtkActor.h>
#include <vtkAlgorithmOutput.h>
#include <vtkCallbackCommand.h>
#include <vtkCellPicker.h>
#include <vtkCommand.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

BenderView::BenderView(vtkAlgorithmOutput* surface, QWidget* parent)
  : QVTKOpenGLNativeWidget(parent)
{
  this->setObjectName("view3d");
  this->setRenderWindow(this->Window);
  this->Window->AddRenderer(this->Renderer);
  this->Renderer->SetBackground(0.12, 0.13, 0.16);
  this->Renderer->SetBackground2(0.32, 0.34, 0.40);
  this->Renderer->GradientBackgroundOn();
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
  // The centerlines: thick lines drawn as tubes, light so that they read through the wall.
  this->CenterlineMapper->ScalarVisibilityOff();
  this->CenterlineActor->SetMapper(this->CenterlineMapper);
  this->CenterlineActor->GetProperty()->SetColor(0.98, 0.92, 0.45);
  this->CenterlineActor->GetProperty()->SetLineWidth(4.0);
  this->CenterlineActor->GetProperty()->SetRenderLinesAsTubes(true);
  this->CenterlineActor->PickableOff();
  this->CenterlineActor->VisibilityOff();
  this->Renderer->AddActor(this->CenterlineActor);

  this->RibbonWidget->SetInteractor(this->Window->GetInteractor());
  this->RibbonWidget->SetCurrentRenderer(this->Renderer);
  this->RibbonWidget->CreateDefaultRepresentation();
  this->RibbonObserver->SetCallback(&BenderView::RibbonCallback);
  this->RibbonObserver->SetClientData(this);
  this->RibbonWidget->AddObserver(vtkCommand::InteractionEvent, this->RibbonObserver);
  this->RibbonWidget->AddObserver(vtkCommand::EndInteractionEvent, this->RibbonObserver);
  this->PickObserver->SetCallback(&BenderView::PickCallback);
  this->PickObserver->SetClientData(this);
  this->Window->GetInteractor()->AddObserver(
    vtkCommand::LeftButtonPressEvent, this->PickObserver, 10.0f);
}

BenderView::~BenderView()
{
  this->RibbonWidget->Off();
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
  this->render();
}

bool BenderView::centerlinesShown() const
{
  return this->CenterlineActor->GetVisibility() != 0;
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

void BenderView::resetCamera()
{
  this->Renderer->ResetCamera();
  this->render();
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
