#include "Private/VoxelRuns.h"

#include "SegmentationErrors.h"
#include "UnionFind.h"

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

namespace bender
{
namespace detail
{

VoxelBox LargestComponentInPlace(const float* values,
  const std::array<std::size_t, 3>& size,
  float lo,
  float hi,
  std::uint8_t* out,
  const ProgressReporter& progress)
{
  const std::string stage = "components";
  progress.Report(stage, 0.0);
  progress.ThrowIfCancelled(stage);
  const std::size_t nx = size[0];
  const std::size_t rows = size[1] * size[2];
  if (size[0] * rows >= std::size_t(std::numeric_limits<std::uint32_t>::max()))
  {
    throw SegmentationError("segmentation: the volume has more than 2^32 voxels");
  }
  struct Run
  {
    std::uint32_t a, b; // x, inclusive
  };
  std::vector<Run> runs;
  BasicUnionFind<std::uint32_t> sets;
  std::vector<std::uint32_t> first(rows + 1, 0);
  const auto joinRows = [&](std::size_t r, std::size_t s)
  {
    std::uint32_t p = first[r];
    std::uint32_t q = first[s];
    while (p < first[r + 1] && q < first[s + 1])
    {
      if (runs[p].a <= runs[q].b && runs[q].a <= runs[p].b)
      {
        sets.Join(p, q);
      }
      if (runs[p].b < runs[q].b)
      {
        ++p;
      }
      else
      {
        ++q;
      }
    }
  };
  const std::size_t reportRows =
    std::max<std::size_t>(1, (std::size_t(1) << 20) / std::max<std::size_t>(nx, 1));
  for (std::size_t r = 0; r < rows; ++r)
  {
    const float* row = values + r * nx;
    // Vectorisable test for an in-window voxel (NaN is never in the window).
    int any = 0;
    for (std::size_t i = 0; i < nx; ++i)
    {
      any |= int(row[i] >= lo) & int(row[i] <= hi);
    }
    if (any)
    {
      for (std::size_t i = 0; i < nx;)
      {
        while (i < nx && !(row[i] >= lo && row[i] <= hi))
        {
          ++i;
        }
        if (i == nx)
        {
          break;
        }
        const std::size_t a = i;
        while (i < nx && row[i] >= lo && row[i] <= hi)
        {
          ++i;
        }
        sets.Add();
        runs.push_back({ std::uint32_t(a), std::uint32_t(i - 1) });
      }
    }
    first[r + 1] = static_cast<std::uint32_t>(runs.size());
    if (first[r + 1] > first[r])
    {
      if (r % size[1] > 0)
      {
        joinRows(r, r - 1);
      }
      if (r >= size[1])
      {
        joinRows(r, r - size[1]);
      }
    }
    if ((r + 1) % reportRows == 0)
    {
      progress.Report(stage, 0.9 * double(r + 1) / double(rows));
      progress.ThrowIfCancelled(stage);
    }
  }
  VoxelBox box;
  if (runs.empty())
  {
    progress.Report(stage, 1.0);
    return box;
  }
  // A set's representative is its first run, so one forward pass of Find points every run
  // straight at it (each earlier run already does), and sums the sets' voxel counts.
  std::vector<std::uint64_t> voxels(runs.size(), 0);
  for (std::size_t p = 0; p < runs.size(); ++p)
  {
    voxels[sets.Find(static_cast<std::uint32_t>(p))] += runs[p].b - runs[p].a + 1;
  }
  std::uint32_t largest = 0;
  for (std::size_t p = 1; p < runs.size(); ++p)
  {
    if (voxels[p] > voxels[largest])
    {
      largest = static_cast<std::uint32_t>(p);
    }
  }
  box.lo = { { long(nx), long(size[1]), long(size[2]) } };
  box.hi = { { -1, -1, -1 } };
  for (std::size_t r = 0; r < rows; ++r)
  {
    for (std::uint32_t p = first[r]; p < first[r + 1]; ++p)
    {
      if (sets.Find(p) != largest)
      {
        continue;
      }
      std::fill(out + r * nx + runs[p].a, out + r * nx + runs[p].b + 1, std::uint8_t(1));
      const long j = long(r % size[1]);
      const long k = long(r / size[1]);
      box.lo[0] = std::min(box.lo[0], long(runs[p].a));
      box.hi[0] = std::max(box.hi[0], long(runs[p].b));
      box.lo[1] = std::min(box.lo[1], j);
      box.hi[1] = std::max(box.hi[1], j);
      box.lo[2] = std::min(box.lo[2], k);
      box.hi[2] = std::max(box.hi[2], k);
    }
  }
  progress.Report(stage, 1.0);
  return box;
}

void FillHolesInPlace(std::uint8_t* voxels,
  const std::array<std::size_t, 3>& size,
  const VoxelBox& box,
  const ProgressReporter& progress)
{
  progress.Report("fill holes", 0.0);
  progress.ThrowIfCancelled("fill holes");
  const long nx = box.hi[0] - box.lo[0] + 1;
  const long ny = box.hi[1] - box.lo[1] + 1;
  const long nz = box.hi[2] - box.lo[2] + 1;
  const auto rowPointer = [&](long j, long k)
  {
    return voxels + std::size_t(box.lo[0]) +
      size[0] * (std::size_t(box.lo[1] + j) + size[1] * std::size_t(box.lo[2] + k));
  };
  struct Run
  {
    std::uint32_t a, b; // box-local x, inclusive
  };
  std::vector<Run> runs;
  std::vector<std::size_t> first(std::size_t(ny * nz) + 1, 0);
  for (long k = 0; k < nz; ++k)
  {
    for (long j = 0; j < ny; ++j)
    {
      const std::uint8_t* row = rowPointer(j, k);
      std::uint8_t any = 0;
      for (long i = 0; i < nx; ++i)
      {
        any |= row[i];
      }
      if (any == 0)
      {
        runs.push_back({ 0, std::uint32_t(nx - 1) });
      }
      else
      {
        for (long i = 0; i < nx;)
        {
          while (i < nx && row[i] != 0)
          {
            ++i;
          }
          if (i == nx)
          {
            break;
          }
          const long a = i;
          while (i < nx && row[i] == 0)
          {
            ++i;
          }
          runs.push_back({ std::uint32_t(a), std::uint32_t(i - 1) });
        }
      }
      first[std::size_t(j + ny * k) + 1] = runs.size();
    }
  }
  progress.ThrowIfCancelled("fill holes");
  // Node runs.size() stands for the outside of the box.
  const auto outside = static_cast<std::uint32_t>(runs.size());
  BasicUnionFind<std::uint32_t> sets(runs.size() + 1);
  const auto joinRows = [&](std::size_t r, std::size_t s)
  {
    std::size_t p = first[r];
    std::size_t q = first[s];
    while (p < first[r + 1] && q < first[s + 1])
    {
      if (runs[p].a <= runs[q].b && runs[q].a <= runs[p].b)
      {
        sets.Join(std::uint32_t(p), std::uint32_t(q));
      }
      if (runs[p].b < runs[q].b)
      {
        ++p;
      }
      else
      {
        ++q;
      }
    }
  };
  for (long k = 0; k < nz; ++k)
  {
    for (long j = 0; j < ny; ++j)
    {
      const std::size_t r = std::size_t(j + ny * k);
      const bool faceRow = j == 0 || j == ny - 1 || k == 0 || k == nz - 1;
      for (std::size_t p = first[r]; p < first[r + 1]; ++p)
      {
        if (faceRow || runs[p].a == 0 || runs[p].b == std::uint32_t(nx - 1))
        {
          sets.Join(std::uint32_t(p), outside);
        }
      }
      if (j > 0)
      {
        joinRows(r, r - 1);
      }
      if (k > 0)
      {
        joinRows(r, r - std::size_t(ny));
      }
    }
  }
  const std::uint32_t outsideRoot = sets.Find(outside);
  for (long k = 0; k < nz; ++k)
  {
    for (long j = 0; j < ny; ++j)
    {
      const std::size_t r = std::size_t(j + ny * k);
      for (std::size_t p = first[r]; p < first[r + 1]; ++p)
      {
        if (sets.Find(std::uint32_t(p)) != outsideRoot)
        {
          std::uint8_t* row = rowPointer(j, k);
          std::fill(row + runs[p].a, row + runs[p].b + 1, std::uint8_t(1));
        }
      }
    }
  }
  progress.Report("fill holes", 1.0);
}

} // namespace detail
} // namespace bender
