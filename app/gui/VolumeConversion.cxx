#include "VolumeConversion.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>

namespace
{
// A grid's voxels (a Volume's or a LabelMap's) as the scalars `Array` named `name` of an image
// with the grid's size, spacing, origin and direction.
template<typename Array, typename Grid>
vtkSmartPointer<vtkImageData> GridToImage(const Grid& grid, const char* name)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(static_cast<int>(grid.geometry.size[0]),
    static_cast<int>(grid.geometry.size[1]),
    static_cast<int>(grid.geometry.size[2]));
  image->SetSpacing(grid.geometry.spacing.data());
  image->SetOrigin(grid.geometry.origin.data());
  image->SetDirectionMatrix(grid.geometry.direction.data());
  vtkNew<Array> scalars;
  scalars->SetName(name);
  scalars->SetNumberOfValues(static_cast<vtkIdType>(grid.voxels.size()));
  std::copy(grid.voxels.begin(), grid.voxels.end(), scalars->GetPointer(0));
  image->GetPointData()->SetScalars(scalars);
  return image;
}
}

vtkSmartPointer<vtkImageData> ToImageData(const bender::Volume& volume)
{
  return GridToImage<vtkFloatArray>(volume, "intensity");
}

vtkSmartPointer<vtkImageData> ToImageData(const bender::LabelMap& mask)
{
  return GridToImage<vtkUnsignedCharArray>(mask, "mask");
}
