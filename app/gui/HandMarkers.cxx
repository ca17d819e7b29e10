#include "HandMarkers.h"

#include <vtkActor.h>
#include <vtkBillboardTextActor3D.h>
#include <vtkCellArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkTextProperty.h>

#include <algorithm>

HandMarkers::HandMarkers()
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  this->TetherData->SetPoints(points);
  this->TetherData->SetLines(lines);
  this->TetherMapper->SetInputData(this->TetherData);
  this->Tether->SetMapper(this->TetherMapper);
  this->Tether->GetProperty()->SetColor(1.0, 0.62, 0.15);
  this->Tether->GetProperty()->SetLineWidth(2.0);
  this->Tether->PickableOff();
  this->Tether->VisibilityOff();
  const char* const names[2] = { "left hand", "right hand" };
  for (int h = 0; h < 2; ++h)
  {
    this->Sphere[h]->SetThetaResolution(20);
    this->Sphere[h]->SetPhiResolution(14);
    this->Mapper[h]->SetInputConnection(this->Sphere[h]->GetOutputPort());
    this->Ball[h]->SetMapper(this->Mapper[h]);
    this->Ball[h]->GetProperty()->SetColor(1.0, 0.62, 0.15);
    this->Ball[h]->GetProperty()->SetOpacity(0.55);
    this->Ball[h]->PickableOff();
    this->Ball[h]->VisibilityOff();
    this->Label[h]->SetInput(names[h]);
    this->Label[h]->GetTextProperty()->SetFontSize(14);
    this->Label[h]->GetTextProperty()->SetColor(1.0, 0.75, 0.35);
    this->Label[h]->GetTextProperty()->ShadowOn();
    this->Label[h]->GetTextProperty()->SetJustificationToCentered();
    this->Label[h]->PickableOff();
    this->Label[h]->VisibilityOff();
  }
}

HandMarkers::~HandMarkers()
{
  if (this->Layer)
  {
    this->Layer->RemoveActor(this->Tether);
    for (int h = 0; h < 2; ++h)
    {
      this->Layer->RemoveActor(this->Ball[h]);
      this->Layer->RemoveViewProp(this->Label[h]);
    }
  }
}

void HandMarkers::attach(vtkRenderer* layer)
{
  this->Layer = layer;
  layer->AddActor(this->Tether);
  for (int h = 0; h < 2; ++h)
  {
    layer->AddActor(this->Ball[h]);
    layer->AddViewProp(this->Label[h]);
  }
}

void HandMarkers::show(const bender::RibbonSpec& hands,
  const std::optional<bender::RibbonSpec>& held)
{
  const bender::RibbonSpec& scaleOf = held ? *held : hands;
  const double length = bender::Distance(scaleOf.start.position, scaleOf.end.position);
  const double radius = std::clamp(0.09 * length, 0.3, 25.0);
  const bender::Vec3 at[2] = { hands.start.position, hands.end.position };
  vtkPoints* points = this->TetherData->GetPoints();
  points->Reset();
  vtkCellArray* lines = this->TetherData->GetLines();
  lines->Reset();
  for (int h = 0; h < 2; ++h)
  {
    this->Position[h][0] = at[h].x;
    this->Position[h][1] = at[h].y;
    this->Position[h][2] = at[h].z;
    this->Sphere[h]->SetCenter(this->Position[h]);
    this->Sphere[h]->SetRadius(radius);
    this->Ball[h]->VisibilityOn();
    this->Label[h]->SetPosition(at[h].x, at[h].y, at[h].z);
    this->Label[h]->SetDisplayOffset(0, 18);
    this->Label[h]->VisibilityOn();
    if (held)
    {
      const bender::Vec3 end = h == 0 ? held->start.position : held->end.position;
      if (bender::Distance(end, at[h]) > 1e-6 * std::max(1.0, length))
      {
        const vtkIdType ids[2] = { points->InsertNextPoint(this->Position[h]),
          points->InsertNextPoint(end.x, end.y, end.z) };
        lines->InsertNextCell(2, ids);
      }
    }
  }
  points->Modified();
  lines->Modified();
  this->TetherData->Modified();
  this->Tether->SetVisibility(lines->GetNumberOfCells() > 0);
  this->Shown = true;
}

void HandMarkers::hide()
{
  this->Tether->VisibilityOff();
  for (int h = 0; h < 2; ++h)
  {
    this->Ball[h]->VisibilityOff();
    this->Label[h]->VisibilityOff();
  }
  this->Shown = false;
}

bool HandMarkers::position(int hand, double position[3]) const
{
  if (!this->Shown || hand < 0 || hand > 1)
    return false;
  std::copy(this->Position[hand], this->Position[hand] + 3, position);
  return true;
}
