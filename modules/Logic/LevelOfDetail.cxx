#include "LevelOfDetail.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkQuadricClustering.h>

#include <cmath>

namespace bender
{

vtkSmartPointer<vtkPolyData> MakeLevelOfDetail(vtkPolyData* surface)
{
  if (!surface || surface->GetNumberOfPoints() == 0)
  {
    return vtkSmartPointer<vtkPolyData>::New();
  }
  // Clustering bins a NaN or infinite coordinate nowhere sensible: such a surface is not
  // decimated (the warp then refuses it with its own message, as without a copy).
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    double p[3];
    surface->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      auto same = vtkSmartPointer<vtkPolyData>::New();
      same->ShallowCopy(surface);
      return same;
    }
  }
  vtkNew<vtkQuadricClustering> decimate;
  decimate->SetInputData(surface);
  decimate->SetNumberOfDivisions(100, 100, 100);
  decimate->AutoAdjustNumberOfDivisionsOn();
  decimate->UseInputPointsOff();
  decimate->CopyCellDataOff();
  decimate->Update();
  vtkSmartPointer<vtkPolyData> copy = decimate->GetOutput();
  return copy;
}

} // namespace bender

vtkStandardNewMacro(vtkBenderLevelOfDetailSource);

void vtkBenderLevelOfDetailSource::SetPrepared(vtkPolyData* input, vtkPolyData* copy)
{
  this->PreparedFor = input;
  this->PreparedTime = input ? input->GetMTime() : 0;
  this->Prepared = copy;
  this->Modified();
}

int vtkBenderLevelOfDetailSource::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (!input || !output)
  {
    return 0;
  }
  if (this->Prepared && input == this->PreparedFor && input->GetMTime() == this->PreparedTime)
  {
    output->ShallowCopy(this->Prepared);
  }
  else
  {
    output->ShallowCopy(bender::MakeLevelOfDetail(input));
    if (input->GetNumberOfPoints() > 0)
    {
      ++this->Builds;
    }
  }
  return 1;
}
