// Both segmentation methods on synthetic volumes: seeded components, hole filling, closing,
// seeds outside or in background, progress and cancellation; the scan-line region growing and
// run-based hole filling against a plain voxel-by-voxel reference on random volumes.
#include "SegmentationTestUtilities.h"

#include "SegmentationErrors.h"
#include "VesselSegmentation.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <deque>
#include <random>

namespace
{

using bender::Point3;

const Point3 BallA{ { 8.0, 10.0, 10.0 } };
const Point3 BallB{ { 22.0, 18.0, 16.0 } };

bender::Volume TwoBalls()
{
  return bender_test::BallsVolume(
    bender_test::CubeGeometry(64, 0.5), { { BallA, 4.0 }, { BallB, 6.0 } });
}

std::size_t CountNear(const bender::LabelMap& mask, const Point3& centre, double radius)
{
  std::size_t n = 0;
  const auto& g = mask.geometry;
  for (std::size_t k = 0; k < g.size[2]; ++k)
    for (std::size_t j = 0; j < g.size[1]; ++j)
      for (std::size_t i = 0; i < g.size[0]; ++i)
      {
        const Point3 p = g.IndexToPhysical({ { double(i), double(j), double(k) } });
        const double d2 = std::pow(p[0] - centre[0], 2) + std::pow(p[1] - centre[1], 2) +
          std::pow(p[2] - centre[2], 2);
        n += (d2 <= radius * radius && mask.voxels[g.LinearIndex(i, j, k)]) ? 1 : 0;
      }
  return n;
}

double BallVoxels(double radius, double spacing)
{
  return 4.0 / 3.0 * M_PI * std::pow(radius / spacing, 3);
}

TEST(VesselSegmentation, ThresholdKeepsOnlyTheSeededComponent)
{
  bender::SegmentationParameters p;
  p.lower = 50.0;
  p.seeds = { BallA };
  const bender::LabelMap mask = bender::SegmentVessels(TwoBalls(), p);
  EXPECT_NEAR(
    double(CountNear(mask, BallA, 5.0)), BallVoxels(4.0, 0.5), 0.05 * BallVoxels(4.0, 0.5));
  EXPECT_EQ(CountNear(mask, BallB, 7.0), 0u);
  EXPECT_EQ(mask.CountInside(), CountNear(mask, BallA, 5.0));
}

TEST(VesselSegmentation, SeveralSeedsKeepSeveralComponentsAndNoSeedKeepsTheLargest)
{
  bender::SegmentationParameters p;
  p.lower = 50.0;
  p.seeds = { BallA, BallB };
  const bender::LabelMap both = bender::SegmentVessels(TwoBalls(), p);
  EXPECT_GT(CountNear(both, BallA, 5.0), 0u);
  EXPECT_GT(CountNear(both, BallB, 7.0), 0u);
  p.seeds.clear();
  const bender::LabelMap largest = bender::SegmentVessels(TwoBalls(), p);
  EXPECT_EQ(CountNear(largest, BallA, 5.0), 0u);
  EXPECT_NEAR(double(largest.CountInside()), BallVoxels(6.0, 0.5), 0.05 * BallVoxels(6.0, 0.5));
}

TEST(VesselSegmentation, InternalHolesAreFilledUnlessAskedNotTo)
{
  bender::Volume v =
    bender_test::BallsVolume(bender_test::CubeGeometry(48, 0.5), { { BallA, 6.0 } });
  // A dark cavity of radius 2 mm inside the ball (a calcification or a noise dropout).
  const auto& g = v.geometry;
  for (std::size_t n = 0; n < v.voxels.size(); ++n)
  {
    const Point3 p =
      g.IndexToPhysical({ { double(n % 48), double((n / 48) % 48), double(n / (48 * 48)) } });
    if (std::hypot(p[0] - BallA[0], p[1] - BallA[1], p[2] - BallA[2]) < 2.0)
    {
      v.voxels[n] = 0.0f;
    }
  }
  bender::SegmentationParameters p;
  p.lower = 50.0;
  p.seeds = { { { BallA[0] + 4.0, BallA[1], BallA[2] } } };
  const bender::LabelMap filled = bender::SegmentVessels(v, p);
  EXPECT_GT(double(CountNear(filled, BallA, 1.9)), 0.95 * BallVoxels(1.9, 0.5));
  p.fillHoles = false;
  const bender::LabelMap hollow = bender::SegmentVessels(v, p);
  EXPECT_EQ(CountNear(hollow, BallA, 1.9), 0u);
}

TEST(VesselSegmentation, ClosingFillsANarrowGroove)
{
  bender::Volume v =
    bender_test::BallsVolume(bender_test::CubeGeometry(48, 0.5), { { BallA, 6.0 } });
  const auto& g = v.geometry;
  // A one-voxel-wide groove, 3 mm deep, cut into the ball's +x side.
  const std::size_t groove = std::size_t(std::lround(BallA[1] / 0.5));
  std::size_t grooveVoxels = 0;
  for (std::size_t k = 0; k < 48; ++k)
    for (std::size_t i = 0; i < 48; ++i)
    {
      const Point3 p = g.IndexToPhysical({ { double(i), double(groove), double(k) } });
      if (p[0] > BallA[0] + 3.0)
      {
        grooveVoxels += v.voxels[g.LinearIndex(i, groove, k)] > 50.0f ? 1 : 0;
        v.voxels[g.LinearIndex(i, groove, k)] = 0.0f;
      }
    }
  ASSERT_GT(grooveVoxels, 20u);
  bender::SegmentationParameters p;
  p.lower = 50.0;
  p.seeds = { BallA };
  const std::size_t open = bender::SegmentVessels(v, p).CountInside();
  p.closingRadius = 1.0;
  const std::size_t closed = bender::SegmentVessels(v, p).CountInside();
  EXPECT_GT(double(closed), double(open) + 0.8 * double(grooveVoxels));
  EXPECT_THROW(
    [&]
    {
      p.closingRadius = 6.0;
      bender::SegmentVessels(v, p);
    }(),
    bender::ParameterError);
}

TEST(VesselSegmentation, SeedsOutsideTheVolumeOrInBackgroundAreRejected)
{
  bender::SegmentationParameters p;
  p.lower = 50.0;
  p.seeds = { { { 100.0, 5.0, 5.0 } } };
  try
  {
    bender::SegmentVessels(TwoBalls(), p);
    ADD_FAILURE() << "no SeedError";
  }
  catch (const bender::SeedError& e)
  {
    EXPECT_NE(std::string(e.what()).find("outside the volume"), std::string::npos) << e.what();
  }
  p.seeds = { { { 1.0, 1.0, 1.0 } } };
  try
  {
    bender::SegmentVessels(TwoBalls(), p);
    ADD_FAILURE() << "no SeedError";
  }
  catch (const bender::SeedError& e)
  {
    EXPECT_NE(std::string(e.what()).find("background"), std::string::npos) << e.what();
  }
  p.seeds = {};
  p.lower = 200.0;
  EXPECT_THROW(bender::SegmentVessels(TwoBalls(), p), bender::SegmentationError);
}

TEST(VesselSegmentation, ReportsProgressAndHonoursCancellation)
{
  std::atomic<bool> cancel{ false };
  bender::ProgressReporter progress;
  std::vector<std::string> stages;
  progress.onProgress = [&](const std::string& stage, double fraction)
  {
    EXPECT_GE(fraction, 0.0);
    EXPECT_LE(fraction, 1.0);
    if (stages.empty() || stages.back() != stage)
    {
      stages.push_back(stage);
    }
  };
  progress.cancel = &cancel;
  bender::SegmentationParameters p;
  p.lower = 50.0;
  p.seeds = { BallA };
  bender::SegmentVessels(TwoBalls(), p, progress);
  EXPECT_NE(std::find(stages.begin(), stages.end(), "connected region"), stages.end());
  EXPECT_NE(std::find(stages.begin(), stages.end(), "fill holes"), stages.end());

  // Cancel from inside the first progress report (as a GUI thread would, asynchronously).
  progress.onProgress = [&](const std::string&, double) { cancel = true; };
  EXPECT_THROW(bender::SegmentVessels(TwoBalls(), p, progress), bender::SegmentationCancelled);
  p.method = bender::SegmentationMethod::Vesselness;
  cancel = false;
  EXPECT_THROW(bender::SegmentVessels(TwoBalls(), p, progress), bender::SegmentationCancelled);
}

/// Reference: breadth-first region growing from the seeds (face connectivity), then hole filling
/// on the bounding box grown by 2 voxels (clipped): background not face-connected to the box's
/// faces becomes foreground. What itk::ConnectedThresholdImageFilter + BinaryFillholeImageFilter
/// did.
std::vector<std::uint8_t> ReferenceSegmentation(const bender::Volume& v,
  float lower,
  const std::vector<std::array<long, 3>>& seeds)
{
  const auto& g = v.geometry;
  const long n[3] = { long(g.size[0]), long(g.size[1]), long(g.size[2]) };
  const auto at = [&](long i, long j, long k) { return std::size_t(i + n[0] * (j + n[1] * k)); };
  std::vector<std::uint8_t> mask(g.VoxelCount(), 0);
  const auto grow = [&](std::deque<std::array<long, 3>> queue,
                      const std::array<long, 3>& lo,
                      const std::array<long, 3>& hi,
                      auto fillable,
                      std::uint8_t value)
  {
    while (!queue.empty())
    {
      const auto c = queue.front();
      queue.pop_front();
      if (!fillable(at(c[0], c[1], c[2])))
      {
        continue;
      }
      mask[at(c[0], c[1], c[2])] = value;
      for (int axis = 0; axis < 3; ++axis)
      {
        for (long step : { -1L, 1L })
        {
          auto d = c;
          d[std::size_t(axis)] += step;
          if (d[std::size_t(axis)] >= lo[std::size_t(axis)] &&
            d[std::size_t(axis)] <= hi[std::size_t(axis)])
          {
            queue.push_back(d);
          }
        }
      }
    }
  };
  const std::array<long, 3> all{ { n[0] - 1, n[1] - 1, n[2] - 1 } };
  grow(
    std::deque<std::array<long, 3>>(seeds.begin(), seeds.end()),
    { { 0, 0, 0 } },
    all,
    [&](std::size_t i) { return mask[i] == 0 && v.voxels[i] >= lower; },
    1);
  std::array<long, 3> lo{ { n[0], n[1], n[2] } };
  std::array<long, 3> hi{ { -1, -1, -1 } };
  for (long k = 0; k < n[2]; ++k)
    for (long j = 0; j < n[1]; ++j)
      for (long i = 0; i < n[0]; ++i)
        if (mask[at(i, j, k)])
        {
          const long c[3] = { i, j, k };
          for (int a = 0; a < 3; ++a)
          {
            lo[std::size_t(a)] = std::min(lo[std::size_t(a)], c[a]);
            hi[std::size_t(a)] = std::max(hi[std::size_t(a)], c[a]);
          }
        }
  for (int a = 0; a < 3; ++a)
  {
    lo[std::size_t(a)] = std::max(0L, lo[std::size_t(a)] - 2);
    hi[std::size_t(a)] = std::min(n[a] - 1, hi[std::size_t(a)] + 2);
  }
  std::deque<std::array<long, 3>> faces;
  for (long k = lo[2]; k <= hi[2]; ++k)
    for (long j = lo[1]; j <= hi[1]; ++j)
      for (long i = lo[0]; i <= hi[0]; ++i)
        if (i == lo[0] || i == hi[0] || j == lo[1] || j == hi[1] || k == lo[2] || k == hi[2])
        {
          faces.push_back({ { i, j, k } });
        }
  grow(
    std::move(faces), lo, hi, [&](std::size_t i) { return mask[i] == 0; }, 2);
  for (long k = lo[2]; k <= hi[2]; ++k)
    for (long j = lo[1]; j <= hi[1]; ++j)
      for (long i = lo[0]; i <= hi[0]; ++i)
      {
        std::uint8_t& m = mask[at(i, j, k)];
        m = m == 2 ? 0 : 1;
      }
  return mask;
}

TEST(VesselSegmentation, RegionGrowingAndHoleFillingMatchAVoxelByVoxelReference)
{
  // Random volumes thresholded near the percolation point: many branches, cavities, tunnels,
  // and a region that reaches the volume's faces.
  std::mt19937 random(7);
  std::size_t filledHoles = 0;
  for (int trial = 0; trial < 6; ++trial)
  {
    bender::ImageGeometry g;
    g.size = {
      { std::size_t(20 + 7 * trial), std::size_t(31 - 2 * trial), std::size_t(17 + 3 * trial) }
    };
    g.spacing = { { 0.5, 0.6, 0.7 } };
    bender::Volume v;
    v.geometry = g;
    std::uniform_real_distribution<float> uniform(0.0f, 100.0f);
    v.voxels.resize(g.VoxelCount());
    for (float& x : v.voxels)
    {
      x = uniform(random);
    }
    const float lower = trial % 2 == 0 ? 62.0f : 55.0f;
    std::vector<std::array<long, 3>> seeds;
    bender::SegmentationParameters p;
    p.lower = lower;
    for (int s = 0; s < 1 + trial % 3; ++s)
    {
      // Choose seeds in the window.
      for (;;)
      {
        const std::array<long, 3> c{
          { long(random() % g.size[0]), long(random() % g.size[1]), long(random() % g.size[2]) }
        };
        if (v.voxels[g.LinearIndex(std::size_t(c[0]), std::size_t(c[1]), std::size_t(c[2]))] >=
          lower)
        {
          seeds.push_back(c);
          p.seeds.push_back(g.IndexToPhysical({ { double(c[0]), double(c[1]), double(c[2]) } }));
          break;
        }
      }
    }
    const bender::LabelMap mask = bender::SegmentVessels(v, p);
    const std::vector<std::uint8_t> expected = ReferenceSegmentation(v, lower, seeds);
    ASSERT_EQ(mask.voxels.size(), expected.size());
    std::size_t differ = 0;
    std::size_t inside = 0;
    for (std::size_t i = 0; i < expected.size(); ++i)
    {
      differ += mask.voxels[i] != expected[i] ? 1 : 0;
      inside += expected[i];
    }
    EXPECT_EQ(differ, 0u) << "trial " << trial << ": " << inside << " voxels inside";
    EXPECT_GT(inside, 20u) << "trial " << trial;
    p.fillHoles = false;
    filledHoles += inside - bender::SegmentVessels(v, p).CountInside();
  }
  EXPECT_GT(filledHoles, 0u) << "the random volumes should have cavities";
}

/// A bright tube of radius 1.2 mm along x and a ball of radius 5 mm.
bender::Volume TubeAndBall(double& tubeVoxels)
{
  bender::Volume v =
    bender_test::BallsVolume(bender_test::CubeGeometry(64, 0.5), { { BallB, 5.0 } });
  const auto& g = v.geometry;
  tubeVoxels = 0;
  for (std::size_t k = 0; k < 64; ++k)
    for (std::size_t j = 0; j < 64; ++j)
      for (std::size_t i = 4; i < 60; ++i)
      {
        const Point3 p = g.IndexToPhysical({ { double(i), double(j), double(k) } });
        const double r = std::hypot(p[1] - 8.0, p[2] - 8.0);
        const float f = float(std::clamp(0.5 - (r - 1.2) / 0.5, 0.0, 1.0));
        float& value = v.voxels[g.LinearIndex(i, j, k)];
        value = std::max(value, 100.0f * f);
        tubeVoxels += r <= 1.2 ? 1 : 0;
      }
  return v;
}

TEST(VesselSegmentation, VesselnessFindsTheTubeAndNotTheBall)
{
  double tubeVoxels = 0;
  const bender::Volume v = TubeAndBall(tubeVoxels);
  bender::SegmentationParameters p;
  p.method = bender::SegmentationMethod::Vesselness;
  p.minRadius = 0.8;
  p.maxRadius = 2.0;
  p.scales = 3;
  p.seeds = { { { 15.0, 8.0, 8.0 } } };
  const bender::LabelMap mask = bender::SegmentVessels(v, p);
  const auto& g = mask.geometry;
  std::size_t inTube = 0;
  for (std::size_t k = 0; k < 64; ++k)
    for (std::size_t j = 0; j < 64; ++j)
      for (std::size_t i = 0; i < 64; ++i)
      {
        const Point3 q = g.IndexToPhysical({ { double(i), double(j), double(k) } });
        inTube += (mask.voxels[g.LinearIndex(i, j, k)] && std::hypot(q[1] - 8.0, q[2] - 8.0) <= 1.7)
          ? 1
          : 0;
      }
  EXPECT_GT(double(inTube), 0.7 * tubeVoxels);
  EXPECT_GT(double(inTube), 0.9 * double(mask.CountInside()))
    << "vesselness leaks outside the tube";
  EXPECT_EQ(CountNear(mask, BallB, 5.5), 0u);
  // The ball centre has low vesselness: as a seed it is background.
  p.seeds = { BallB };
  EXPECT_THROW(bender::SegmentVessels(v, p), bender::SeedError);
}

TEST(VesselSegmentation, LevelSetRefinementPullsAnUndersegmentationOntoTheEdge)
{
  // A blurred ball of radius 6 mm segmented with a too-high window: radius ~5 mm.
  bender::Volume v =
    bender_test::BallsVolume(bender_test::CubeGeometry(48, 0.5), { { BallA, 6.0 } });
  bender::Volume blurred = v;
  const auto& g = v.geometry;
  for (std::size_t n = 0; n < v.voxels.size(); ++n)
  {
    const Point3 p =
      g.IndexToPhysical({ { double(n % 48), double((n / 48) % 48), double(n / (48 * 48)) } });
    const double d = std::hypot(p[0] - BallA[0], p[1] - BallA[1], p[2] - BallA[2]) - 6.0;
    blurred.voxels[n] = float(100.0 / (1.0 + std::exp(d / 0.6)));
  }
  bender::SegmentationParameters p;
  p.lower = 84.0;
  p.seeds = { BallA };
  const double before = double(bender::SegmentVessels(blurred, p).CountInside());
  p.levelSetIterations = 200;
  p.levelSetPropagation = 0.5;
  const double after = double(bender::SegmentVessels(blurred, p).CountInside());
  const double truth = BallVoxels(6.0, 0.5);
  EXPECT_LT(std::abs(after - truth), 0.5 * std::abs(before - truth))
    << "before " << before << " after " << after << " truth " << truth;
}

TEST(VesselSegmentation, ParametersOutsideTheirRangesAreRejected)
{
  bender::SegmentationParameters p;
  p.lower = 10;
  p.upper = 5;
  EXPECT_THROW(bender::ValidateSegmentationParameters(p), bender::ParameterError);
  p = {};
  p.minRadius = 3.0;
  p.maxRadius = 2.0;
  EXPECT_THROW(bender::ValidateSegmentationParameters(p), bender::ParameterError);
  p = {};
  p.vesselnessThreshold = 1.5;
  EXPECT_THROW(bender::ValidateSegmentationParameters(p), bender::ParameterError);
  p = {};
  p.seeds = { { { std::nan(""), 0, 0 } } };
  EXPECT_THROW(bender::ValidateSegmentationParameters(p), bender::ParameterError);
  EXPECT_NO_THROW(bender::ValidateSegmentationParameters(bender::SegmentationParameters{}));
}

} // namespace
