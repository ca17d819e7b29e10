#include "ProblemOverlay.h"

#include <vtkActor.h>
#include <vtkBillboardTextActor3D.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkTextProperty.h>

ProblemOverlay::ProblemOverlay(vtkRenderer* renderer, vtkRenderer* topLayer)
  : Renderer(renderer)
  , TopLayer(topLayer ? topLayer : renderer)
{
  this->Mapper->SetInputData(this->Triangles);
  this->Mapper->ScalarVisibilityOff();
  // On the surface it marks: drawn slightly in front of the coincident vessel triangles.
  this->Mapper->SetResolveCoincidentTopologyToPolygonOffset();
  this->Mapper->SetRelativeCoincidentTopologyPolygonOffsetParameters(-4, -40);
  this->Mapper->SetRelativeCoincidentTopologyLineOffsetParameters(-4, -60);
  this->Actor->SetMapper(this->Mapper);
  vtkProperty* property = this->Actor->GetProperty();
  property->SetColor(1.0, 0.85, 0.0);
  property->SetEdgeColor(0.9, 0.0, 0.0);
  property->EdgeVisibilityOn();
  property->SetLineWidth(3.0);
  property->SetAmbient(0.6);
  property->SetDiffuse(0.4);
  property->BackfaceCullingOff();
  this->Actor->PickableOff();
  this->Actor->VisibilityOff();
  if (this->Renderer)
  {
    this->Renderer->AddActor(this->Actor);
  }
  // The narrowest point: a translucent magenta ball around the lumen there, and its label.
  this->Ball->SetThetaResolution(24);
  this->Ball->SetPhiResolution(16);
  this->BallMapper->SetInputConnection(this->Ball->GetOutputPort());
  this->BallActor->SetMapper(this->BallMapper);
  this->BallActor->GetProperty()->SetColor(0.95, 0.1, 0.85);
  this->BallActor->GetProperty()->SetOpacity(0.45);
  this->BallActor->PickableOff();
  this->BallActor->VisibilityOff();
  this->Label->GetTextProperty()->SetFontSize(15);
  this->Label->GetTextProperty()->SetColor(1.0, 0.55, 0.95);
  this->Label->GetTextProperty()->BoldOn();
  this->Label->GetTextProperty()->ShadowOn();
  this->Label->GetTextProperty()->SetJustificationToCentered();
  this->Label->SetDisplayOffset(0, 22);
  this->Label->PickableOff();
  this->Label->VisibilityOff();
  if (this->TopLayer)
  {
    this->TopLayer->AddActor(this->BallActor);
    this->TopLayer->AddViewProp(this->Label);
  }
}

ProblemOverlay::~ProblemOverlay()
{
  if (this->Renderer)
  {
    this->Renderer->RemoveActor(this->Actor);
  }
  if (this->TopLayer)
  {
    this->TopLayer->RemoveActor(this->BallActor);
    this->TopLayer->RemoveViewProp(this->Label);
  }
}

void ProblemOverlay::Show(vtkPolyData* triangles)
{
  if (!triangles || triangles->GetNumberOfCells() == 0)
  {
    this->Hide();
    return;
  }
  this->Triangles->DeepCopy(triangles);
  this->Triangles->Modified();
  this->Actor->VisibilityOn();
}

void ProblemOverlay::ShowNarrowing(const double point[3], double radius, const std::string& label)
{
  this->Ball->SetCenter(point[0], point[1], point[2]);
  this->Ball->SetRadius(1.6 * radius);
  this->BallActor->VisibilityOn();
  this->Label->SetPosition(point[0], point[1], point[2]);
  this->Label->SetInput(label.c_str());
  this->Label->VisibilityOn();
}

void ProblemOverlay::Hide()
{
  this->Triangles->Initialize();
  this->Triangles->Modified();
  this->Actor->VisibilityOff();
  this->BallActor->VisibilityOff();
  this->Label->VisibilityOff();
}

bool ProblemOverlay::IsNarrowingShown() const
{
  return this->BallActor->GetVisibility() != 0;
}

bool ProblemOverlay::GetNarrowing(double point[3], std::string& label) const
{
  if (!this->IsNarrowingShown())
  {
    return false;
  }
  this->Ball->GetCenter(point);
  label = this->Label->GetInput() ? this->Label->GetInput() : "";
  return true;
}

bool ProblemOverlay::IsShown() const
{
  return this->Actor->GetVisibility() != 0;
}

vtkIdType ProblemOverlay::GetNumberOfTriangles() const
{
  return this->IsShown() ? this->Triangles->GetNumberOfCells() : 0;
}

vtkActor* ProblemOverlay::GetActor() const
{
  return this->Actor.GetPointer();
}
