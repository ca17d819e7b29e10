#include "ProblemOverlay.h"

#include <vtkActor.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>

ProblemOverlay::ProblemOverlay(vtkRenderer* renderer)
  : Renderer(renderer)
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
}

ProblemOverlay::~ProblemOverlay()
{
  if (this->Renderer)
  {
    this->Renderer->RemoveActor(this->Actor);
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

void ProblemOverlay::Hide()
{
  this->Triangles->Initialize();
  this->Triangles->Modified();
  this->Actor->VisibilityOff();
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
