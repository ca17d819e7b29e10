#include "SliceGeometry.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkMatrix4x4.h>
#include <vtkPointData.h>

#include <algorithm>
#include <cmath>
#include <vector>

const unsigned char SliceColours[3][3] = { { 242, 97, 89 }, { 115, 217, 102 }, { 242, 217, 77 } };
const char* const SliceNames[3] = { "Axial", "Coronal", "Sagittal" };

int SliceAxis(int view)
{
  return view == 0 ? 2 : (view == 1 ? 1 : 0);
}

const char* PatientLetter(const double v[3])
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

vtkSmartPointer<vtkImageData> Unplaced(vtkImageData* image)
{
  auto grid = vtkSmartPointer<vtkImageData>::New();
  grid->SetDimensions(image->GetDimensions());
  grid->SetSpacing(image->GetSpacing());
  grid->SetOrigin(0, 0, 0);
  grid->GetPointData()->SetScalars(image->GetPointData()->GetScalars());
  return grid;
}

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

void VoxelBox(vtkImageData* image, double bounds[6])
{
  int dims[3];
  image->GetDimensions(dims);
  const double* spacing = image->GetSpacing();
  vtkSmartPointer<vtkMatrix4x4> placement = Placement(image);
  for (int axis = 0; axis < 3; ++axis)
  {
    bounds[2 * axis] = VTK_DOUBLE_MAX;
    bounds[2 * axis + 1] = VTK_DOUBLE_MIN;
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
      bounds[2 * axis] = std::min(bounds[2 * axis], world[axis]);
      bounds[2 * axis + 1] = std::max(bounds[2 * axis + 1], world[axis]);
    }
  }
}

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
