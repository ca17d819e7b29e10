#include "VolumeConversion.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>

namespace
{
vtkSmartPointer<vtkImageData> EmptyImage(const bender::ImageGeometry& geometry)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(static_cast<int>(geometry.size[0]),
    static_cast<int>(geometry.size[1]),
    static_cast<int>(geometry.size[2]));
  image->SetSpacing(geometry.spacing.data());
  image->SetOrigin(geometry.origin.data());
  image->SetDirectionMatrix(geometry.direction.data());
  return image;
}
}

vtkSmartPointer<vtkImageData> ToImageData(const bender::Volume& volume)
{
  auto image = EmptyImage(volume.geometry);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName("intensity");
  scalars->SetNumberOfValues(static_cast<vtkIdType>(volume.voxels.size()));
  std::copy(volume.voxels.begin(), volume.voxels.end(), scalars->GetPointer(0));
  image->GetPointData()->SetScalars(scalars);
  return image;
}

vtkSmartPointer<vtkImageData> ToImageData(const bender::LabelMap& mask)
{
  auto image = EmptyImage(mask.geometry);
  vtkNew<vtkUnsignedCharArray> scalars;
  scalars->SetName("mask");
  scalars->SetNumberOfValues(static_cast<vtkIdType>(mask.voxels.size()));
  std::copy(mask.voxels.begin(), mask.voxels.end(), scalars->GetPointer(0));
  image->GetPointData()->SetScalars(scalars);
  return image;
}
