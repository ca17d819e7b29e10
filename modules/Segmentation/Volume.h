#ifndef bender_Volume_h
#define bender_Volume_h

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace bender
{

using Point3 = std::array<double, 3>;

/// Where the voxels of a volume lie in the patient frame. Frame: LPS (DICOM/ITK convention),
/// unit: mm. The physical point of voxel index (i, j, k) is
///   origin + direction * (spacing .* (i, j, k)),
/// i.e. the origin is the centre of voxel (0, 0, 0) and column c of `direction` is the LPS
/// direction of index axis c (an orthonormal matrix; oblique acquisitions have off-diagonal terms).
struct ImageGeometry
{
  std::array<std::size_t, 3> size{ { 0, 0, 0 } };
  /// mm, each > 0.
  std::array<double, 3> spacing{ { 1.0, 1.0, 1.0 } };
  /// LPS mm, centre of voxel (0, 0, 0).
  Point3 origin{ { 0.0, 0.0, 0.0 } };
  /// Row-major 3x3: direction[3 * row + column].
  std::array<double, 9> direction{ { 1, 0, 0, 0, 1, 0, 0, 0, 1 } };

  std::size_t VoxelCount() const { return size[0] * size[1] * size[2]; }
  std::size_t LinearIndex(std::size_t i, std::size_t j, std::size_t k) const
  {
    return i + size[0] * (j + size[1] * k);
  }
  /// Continuous index (voxel centres at integers) to LPS mm.
  Point3 IndexToPhysical(const Point3& index) const;
  /// LPS mm to continuous index (inverse of IndexToPhysical; direction assumed orthonormal).
  Point3 PhysicalToIndex(const Point3& point) const;
  /// True when the point lies inside the volume's voxels (within half a voxel of the centres).
  bool ContainsPhysical(const Point3& point) const;
};

/// A scalar volume, intensities cast to float, x index fastest.
struct Volume
{
  ImageGeometry geometry;
  std::vector<float> voxels;
};

/// A binary mask on a volume's grid: 1 inside the segmented vessels, 0 elsewhere.
struct LabelMap
{
  ImageGeometry geometry;
  std::vector<std::uint8_t> voxels;

  std::size_t CountInside() const;
};

/// Trilinear resampling of a volume onto `size` voxels covering the same physical box (voxel
/// edges aligned with the input's). Used to make large benchmark volumes. Throws ParameterError
/// for a zero size.
Volume ResampleVolume(const Volume& input, const std::array<std::size_t, 3>& size);

} // namespace bender

#endif
