// Segmentation without a seed (the largest component of the window, as for a head MRI): the
// run-based labelling against a breadth-first reference on random volumes, and the no-seed path
// against the seeded path on the aneurysm phantom (the seed lies in the largest component, so
// both masks must be equal voxel for voxel); and the resampling used to vary the grid.

#include "SegmentationTestUtilities.h"

#include "MeshIO.h"
#include "VesselPhantom.h"
#include "VesselSegmentation.h"

#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <random>
#include <vector>

namespace
{

/// Reference: every face-connected component of the window [lower, upper] by breadth-first
/// search, voxel by voxel; returns the largest one (ties: the one whose first voxel comes first
/// in raster order) as a 0/1 mask, and its size and the runner-up's size.
struct Reference
{
  std::vector<std::uint8_t> mask;
  std::size_t largest = 0;
  std::size_t second = 0;
};

Reference LargestByBreadthFirst(const bender::Volume& v, float lower, float upper)
{
  const auto& g = v.geometry;
  const long n[3] = { long(g.size[0]), long(g.size[1]), long(g.size[2]) };
  const auto in = [&](std::size_t i) { return v.voxels[i] >= lower && v.voxels[i] <= upper; };
  std::vector<std::uint32_t> label(g.VoxelCount(), 0);
  std::vector<std::size_t> sizes{ 0 };
  for (std::size_t start = 0; start < g.VoxelCount(); ++start)
  {
    if (label[start] != 0 || !in(start))
    {
      continue;
    }
    const auto id = static_cast<std::uint32_t>(sizes.size());
    sizes.push_back(0);
    std::deque<std::size_t> queue{ start };
    label[start] = id;
    while (!queue.empty())
    {
      const std::size_t i = queue.front();
      queue.pop_front();
      ++sizes[id];
      const long x = long(i % g.size[0]);
      const long y = long((i / g.size[0]) % g.size[1]);
      const long z = long(i / (g.size[0] * g.size[1]));
      const long d[6][3] = {
        { -1, 0, 0 }, { 1, 0, 0 }, { 0, -1, 0 }, { 0, 1, 0 }, { 0, 0, -1 }, { 0, 0, 1 }
      };
      for (const auto& e : d)
      {
        const long a = x + e[0];
        const long b = y + e[1];
        const long c = z + e[2];
        if (a < 0 || b < 0 || c < 0 || a >= n[0] || b >= n[1] || c >= n[2])
        {
          continue;
        }
        const std::size_t j = g.LinearIndex(std::size_t(a), std::size_t(b), std::size_t(c));
        if (label[j] == 0 && in(j))
        {
          label[j] = id;
          queue.push_back(j);
        }
      }
    }
  }
  Reference r;
  r.mask.assign(g.VoxelCount(), 0);
  std::uint32_t best = 0;
  for (std::uint32_t id = 1; id < sizes.size(); ++id)
  {
    if (sizes[id] > r.largest)
    {
      r.second = r.largest;
      r.largest = sizes[id];
      best = id;
    }
    else if (sizes[id] > r.second)
    {
      r.second = sizes[id];
    }
  }
  for (std::size_t i = 0; i < label.size(); ++i)
  {
    r.mask[i] = label[i] == best && best != 0 ? 1 : 0;
  }
  return r;
}

bender::Volume Noise(const std::array<std::size_t, 3>& size, std::uint32_t seed)
{
  bender::Volume v;
  v.geometry.size = size;
  v.geometry.spacing = { { 0.5, 0.7, 0.9 } };
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> value(0.0f, 1.0f);
  v.voxels.resize(v.geometry.VoxelCount());
  for (float& x : v.voxels)
  {
    x = value(random);
  }
  return v;
}

std::size_t CountDifferences(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b)
{
  std::size_t d = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i)
  {
    d += a[i] != b[i] ? 1 : 0;
  }
  return d + (a.size() > b.size() ? a.size() - b.size() : b.size() - a.size());
}

} // namespace

TEST(LargestComponent, EqualsABreadthFirstLabellingOnRandomVolumes)
{
  // Random voxels thresholded near the percolation threshold of face connectivity (~0.31 of
  // the voxels in): many components of every shape, runs that touch the volume's faces, and
  // rows of one voxel (size 1 along x).
  const std::array<std::size_t, 3> sizes[] = {
    { { 23, 19, 17 } }, { { 1, 40, 30 } }, { { 64, 1, 9 } }, { { 40, 37, 1 } }, { { 31, 29, 27 } }
  };
  const float windows[][2] = { { 0.0f, 0.30f }, { 0.69f, 1.0f }, { 0.2f, 0.55f }, { 0.0f, 0.25f } };
  int compared = 0;
  std::uint32_t seed = 7;
  for (const auto& size : sizes)
  {
    for (const auto& w : windows)
    {
      const bender::Volume v = Noise(size, ++seed);
      const Reference expected = LargestByBreadthFirst(v, w[0], w[1]);
      if (expected.largest == 0 || expected.largest == expected.second)
      {
        continue; // no voxel in the window, or a tie: covered below
      }
      bender::SegmentationParameters p;
      p.lower = w[0];
      p.upper = w[1];
      p.fillHoles = false;
      const bender::LabelMap mask = bender::SegmentVessels(v, p);
      EXPECT_EQ(mask.CountInside(), expected.largest)
        << size[0] << "x" << size[1] << "x" << size[2];
      EXPECT_EQ(CountDifferences(mask.voxels, expected.mask), 0u)
        << size[0] << "x" << size[1] << "x" << size[2] << " window [" << w[0] << ", " << w[1]
        << "]";
      ++compared;
    }
  }
  EXPECT_GE(compared, 15);
}

TEST(LargestComponent, TiesKeepTheComponentThatStartsFirstAndNanIsBackground)
{
  // Two equal bars; the one in the first rows wins. NaN and values above the window split a bar.
  bender::Volume v;
  v.geometry.size = { { 10, 6, 4 } };
  v.voxels.assign(v.geometry.VoxelCount(), 0.0f);
  for (std::size_t x = 1; x < 9; ++x)
  {
    v.voxels[v.geometry.LinearIndex(x, 4, 3)] = 1.0f; // later in raster order
    v.voxels[v.geometry.LinearIndex(x, 1, 0)] = 1.0f; // earlier
  }
  bender::SegmentationParameters p;
  p.lower = 0.5;
  p.upper = 1.5;
  p.fillHoles = false;
  bender::LabelMap mask = bender::SegmentVessels(v, p);
  EXPECT_EQ(mask.CountInside(), 8u);
  EXPECT_EQ(mask.voxels[v.geometry.LinearIndex(1, 1, 0)], 1);
  EXPECT_EQ(mask.voxels[v.geometry.LinearIndex(1, 4, 3)], 0);

  // Cut the first bar into 3 + 4 voxels with a NaN, the second into 2 + 5 with a value above
  // the window: now the 5-voxel piece of the second bar is the largest.
  v.voxels[v.geometry.LinearIndex(4, 1, 0)] = std::numeric_limits<float>::quiet_NaN();
  v.voxels[v.geometry.LinearIndex(3, 4, 3)] = 2.0f;
  mask = bender::SegmentVessels(v, p);
  EXPECT_EQ(mask.CountInside(), 5u);
  for (std::size_t x = 4; x < 9; ++x)
  {
    EXPECT_EQ(mask.voxels[v.geometry.LinearIndex(x, 4, 3)], 1) << x;
  }

  // Nothing in the window: one clear error, as before.
  p.lower = 5.0;
  p.upper = 6.0;
  EXPECT_THROW(bender::SegmentVessels(v, p), bender::SegmentationError);
}

TEST(LargestComponent, NoSeedEqualsTheSeededComponentOnThePhantom)
{
  vtkSmartPointer<vtkPolyData> truth =
    bender::ReadMesh(bender_test::ExternalData("aneurysm_data.stl"));
  const bender::Phantom phantom = bender::MakeVesselPhantom(truth);
  // The phantom's grid and an anisotropic resampling of it (other row lengths and run layout).
  const auto& g = phantom.volume.geometry;
  const bender::Volume resampled =
    bender::ResampleVolume(phantom.volume, { { g.size[0] * 3 / 4, g.size[1] + 7, g.size[2] / 2 } });
  for (const bender::Volume* volume : { &phantom.volume, &resampled })
  {
    for (const bool fillHoles : { true, false })
    {
      bender::SegmentationParameters seeded;
      seeded.lower = phantom.midIntensity;
      seeded.fillHoles = fillHoles;
      seeded.seeds = { phantom.seed };
      bender::SegmentationParameters largest = seeded;
      largest.seeds.clear();
      const bender::LabelMap a = bender::SegmentVessels(*volume, seeded);
      const bender::LabelMap b = bender::SegmentVessels(*volume, largest);
      EXPECT_GT(a.CountInside(), 10000u);
      EXPECT_EQ(a.voxels.size(), b.voxels.size());
      EXPECT_EQ(CountDifferences(a.voxels, b.voxels), 0u)
        << volume->geometry.size[0] << "x" << volume->geometry.size[1] << "x"
        << volume->geometry.size[2] << (fillHoles ? " with" : " without") << " hole filling";
    }
  }
}

// ResampleVolume (slices resampled in parallel with vtkSMPTools): trilinear interpolation
// reproduces a linear ramp of the physical coordinates exactly up to float rounding, on an
// oblique grid, and two runs give the same voxels bit for bit.
TEST(ResampleVolume, ReproducesALinearRampAndIsDeterministic)
{
  bender::Volume v;
  v.geometry.size = { { 23, 17, 31 } };
  v.geometry.spacing = { { 0.7, 1.1, 0.5 } };
  v.geometry.origin = { { -3.0, 4.0, 10.0 } };
  const double c = std::cos(0.3), s = std::sin(0.3);
  v.geometry.direction = { { c, -s, 0, s, c, 0, 0, 0, 1 } };
  const auto ramp = [](const bender::Point3& x) { return 2.0 * x[0] - 3.0 * x[1] + 0.5 * x[2]; };
  v.voxels.resize(v.geometry.VoxelCount());
  for (std::size_t k = 0; k < v.geometry.size[2]; ++k)
  {
    for (std::size_t j = 0; j < v.geometry.size[1]; ++j)
    {
      for (std::size_t i = 0; i < v.geometry.size[0]; ++i)
      {
        v.voxels[v.geometry.LinearIndex(i, j, k)] = static_cast<float>(
          ramp(v.geometry.IndexToPhysical({ { double(i), double(j), double(k) } })));
      }
    }
  }
  const std::array<std::size_t, 3> size{ { 31, 12, 47 } };
  const bender::Volume a = bender::ResampleVolume(v, size);
  const bender::Volume b = bender::ResampleVolume(v, size);
  ASSERT_EQ(a.voxels.size(), size[0] * size[1] * size[2]);
  EXPECT_EQ(a.voxels, b.voxels);
  double worst = 0.0;
  for (std::size_t k = 0; k < size[2]; ++k)
  {
    for (std::size_t j = 0; j < size[1]; ++j)
    {
      for (std::size_t i = 0; i < size[0]; ++i)
      {
        // Inside the input's voxel centres only (outside, the resampling clamps).
        const bender::Point3 x =
          a.geometry.IndexToPhysical({ { double(i), double(j), double(k) } });
        const bender::Point3 index = v.geometry.PhysicalToIndex(x);
        bool inside = true;
        for (int d = 0; d < 3; ++d)
        {
          inside = inside && index[d] >= 0 && index[d] <= double(v.geometry.size[d] - 1);
        }
        if (inside)
        {
          worst = std::max(worst, std::abs(a.voxels[a.geometry.LinearIndex(i, j, k)] - ramp(x)));
        }
      }
    }
  }
  EXPECT_LT(worst, 1e-3);
}
