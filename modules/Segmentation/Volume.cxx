#include "Volume.h"

#include "SegmentationErrors.h"

#include <vtkSMPTools.h>

#include <algorithm>
#include <cmath>

namespace bender
{

Point3 ImageGeometry::IndexToPhysical(const Point3& index) const
{
  Point3 p = this->origin;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      p[r] += this->direction[3 * r + c] * this->spacing[c] * index[c];
    }
  }
  return p;
}

Point3 ImageGeometry::PhysicalToIndex(const Point3& point) const
{
  Point3 index{ { 0, 0, 0 } };
  for (int c = 0; c < 3; ++c)
  {
    double sum = 0.0;
    // Orthonormal direction: its inverse is its transpose.
    for (int r = 0; r < 3; ++r)
    {
      sum += this->direction[3 * r + c] * (point[r] - this->origin[r]);
    }
    index[c] = sum / this->spacing[c];
  }
  return index;
}

bool ImageGeometry::ContainsPhysical(const Point3& point) const
{
  const Point3 index = this->PhysicalToIndex(point);
  for (int c = 0; c < 3; ++c)
  {
    if (!(index[c] >= -0.5 && index[c] <= static_cast<double>(this->size[c]) - 0.5))
    {
      return false;
    }
  }
  return true;
}

std::size_t LabelMap::CountInside() const
{
  return static_cast<std::size_t>(
    std::count_if(this->voxels.begin(), this->voxels.end(), [](std::uint8_t v) { return v != 0; }));
}

Volume ResampleVolume(const Volume& input, const std::array<std::size_t, 3>& size)
{
  const ImageGeometry& in = input.geometry;
  if (size[0] == 0 || size[1] == 0 || size[2] == 0 || in.VoxelCount() == 0)
  {
    throw ParameterError("resample: empty input or zero output size");
  }
  Volume out;
  out.geometry = in;
  out.geometry.size = size;
  Point3 shift{ { 0, 0, 0 } };
  std::array<double, 3> scale{ { 0, 0, 0 } };
  for (int c = 0; c < 3; ++c)
  {
    const double extent = in.spacing[c] * static_cast<double>(in.size[c]);
    out.geometry.spacing[c] = extent / static_cast<double>(size[c]);
    // Keep the outer voxel edges: first output centre sits half an output voxel inside.
    shift[c] = 0.5 * (out.geometry.spacing[c] - in.spacing[c]);
    scale[c] = out.geometry.spacing[c] / in.spacing[c];
  }
  out.geometry.origin = in.IndexToPhysical(
    { { shift[0] / in.spacing[0], shift[1] / in.spacing[1], shift[2] / in.spacing[2] } });
  out.voxels.resize(out.geometry.VoxelCount());

  auto work = [&](std::size_t k0, std::size_t k1)
  {
    std::vector<std::size_t> i0(size[0]);
    std::vector<float> fx(size[0]);
    for (std::size_t i = 0; i < size[0]; ++i)
    {
      const double x = std::clamp(
        (static_cast<double>(i) + 0.5) * scale[0] - 0.5, 0.0, static_cast<double>(in.size[0] - 1));
      i0[i] = std::min(static_cast<std::size_t>(x), in.size[0] > 1 ? in.size[0] - 2 : 0);
      fx[i] = in.size[0] > 1 ? static_cast<float>(x - static_cast<double>(i0[i])) : 0.0f;
    }
    const std::size_t sx = in.size[0] > 1 ? 1 : 0;
    const std::size_t sy = in.size[1] > 1 ? in.size[0] : 0;
    const std::size_t sz = in.size[2] > 1 ? in.size[0] * in.size[1] : 0;
    for (std::size_t k = k0; k < k1; ++k)
    {
      const double z = std::clamp(
        (static_cast<double>(k) + 0.5) * scale[2] - 0.5, 0.0, static_cast<double>(in.size[2] - 1));
      const std::size_t kz =
        std::min(static_cast<std::size_t>(z), in.size[2] > 1 ? in.size[2] - 2 : 0);
      const float fz = in.size[2] > 1 ? static_cast<float>(z - static_cast<double>(kz)) : 0.0f;
      for (std::size_t j = 0; j < size[1]; ++j)
      {
        const double y = std::clamp((static_cast<double>(j) + 0.5) * scale[1] - 0.5,
          0.0,
          static_cast<double>(in.size[1] - 1));
        const std::size_t jy =
          std::min(static_cast<std::size_t>(y), in.size[1] > 1 ? in.size[1] - 2 : 0);
        const float fy = in.size[1] > 1 ? static_cast<float>(y - static_cast<double>(jy)) : 0.0f;
        float* row = out.voxels.data() + out.geometry.LinearIndex(0, j, k);
        for (std::size_t i = 0; i < size[0]; ++i)
        {
          const float* p = input.voxels.data() + in.LinearIndex(i0[i], jy, kz);
          const float a = fx[i];
          const float c00 = p[0] + a * (p[sx] - p[0]);
          const float c10 = p[sy] + a * (p[sy + sx] - p[sy]);
          const float c01 = p[sz] + a * (p[sz + sx] - p[sz]);
          const float c11 = p[sz + sy] + a * (p[sz + sy + sx] - p[sz + sy]);
          const float c0 = c00 + fy * (c10 - c00);
          const float c1 = c01 + fy * (c11 - c01);
          row[i] = c0 + fz * (c1 - c0);
        }
      }
    }
  };
  // Each output slice is independent of the others.
  vtkSMPTools::For(0,
    static_cast<vtkIdType>(size[2]),
    [&](vtkIdType k0, vtkIdType k1)
    { work(static_cast<std::size_t>(k0), static_cast<std::size_t>(k1)); });
  return out;
}

} // namespace bender
