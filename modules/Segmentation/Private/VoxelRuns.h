#ifndef bender_Private_VoxelRuns_h
#define bender_Private_VoxelRuns_h

// Internal to bender_segmentation: the two passes of SegmentVessels that work on the runs of
// voxels of x-rows instead of voxel by voxel (the largest component of a window, the holes of a
// mask), on raw buffers of `size` voxels in raster order (x fastest).

#include "Progress.h"

#include <array>
#include <cstddef>
#include <cstdint>

namespace bender
{
namespace detail
{

/// Voxel index box [lo, hi] (inclusive); empty while hi < lo.
struct VoxelBox
{
  std::array<long, 3> lo{ { 0, 0, 0 } };
  std::array<long, 3> hi{ { -1, -1, -1 } };
  bool Empty() const { return this->hi[0] < this->lo[0]; }
};

/// The largest face-connected component of the window [lo, hi] of `values` (a raw buffer of
/// `size` voxels), written as 1 into `out` (all zero on entry). Same component as
/// itk::ConnectedComponentImageFilter (FullyConnected off) + RelabelComponentImageFilter label 1,
/// but on runs instead of voxels: every x-row is cut into runs of in-window voxels, runs of
/// face-adjacent rows (j - 1 and k - 1) that overlap in x are joined (union-find, the root of a
/// set is its first run in raster order), and the runs of the largest set (ties: the set that
/// starts first in raster order) are written out. One read of the volume; rows without an
/// in-window voxel cost one vectorised pass. Returns the bounding box of the component (empty
/// when no voxel is in the window). Reports progress and honours cancellation every few rows.
VoxelBox LargestComponentInPlace(const float* values,
  const std::array<std::size_t, 3>& size,
  float lo,
  float hi,
  std::uint8_t* out,
  const ProgressReporter& progress);

/// Fills the cavities of the 0/1 mask inside `box` in place: background voxels that are not
/// face-connected to the box's faces through background become foreground. Same result as
/// itk::BinaryFillholeImageFilter (FullyConnected off) on the box, but on runs instead of voxels:
/// the background of every x-row of the box is cut into runs (an empty row is one run), runs of
/// face-adjacent rows that overlap in x are joined (union-find), and the runs not joined to the
/// box's faces are the holes. One read of the box; the background (most of the box) is never
/// flood-filled voxel by voxel.
void FillHolesInPlace(std::uint8_t* voxels,
  const std::array<std::size_t, 3>& size,
  const VoxelBox& box,
  const ProgressReporter& progress);

} // namespace detail
} // namespace bender

#endif
