// The segment workflow's plausibility rule (SegmentationWarning, SegmentLoadedVolume) and the
// demo's one fallback (SegmentDemoVesselOrFallBack).
#include "SegmentVolume.h"
#include "DemoPipeline.h"

#include "BenderErrors.h"
#include "MeshIO.h"

#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>

using namespace bender;

namespace
{

// size^3 voxels of 1 mm, background 100, a bright (400) ball of `radius` voxels at the centre.
Volume BallVolume(std::size_t size, double radius)
{
  Volume volume;
  volume.geometry.size = { size, size, size };
  volume.voxels.assign(volume.geometry.VoxelCount(), 100.0f);
  const double c = 0.5 * (static_cast<double>(size) - 1.0);
  for (std::size_t k = 0; k < size; ++k)
    for (std::size_t j = 0; j < size; ++j)
      for (std::size_t i = 0; i < size; ++i)
      {
        const double x = double(i) - c, y = double(j) - c, z = double(k) - c;
        if (std::sqrt(x * x + y * y + z * z) < radius)
          volume.voxels[volume.geometry.LinearIndex(i, j, k)] = 400.0f;
      }
  return volume;
}

bool Contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

}

TEST(SegmentationWarning, ItWarnsBelowTheMinimumAndNamesWhatWasKept)
{
  EXPECT_TRUE(SegmentationWarning(250.0, true, 5000, MinimumSurfacePoints).empty());
  const std::string few = SegmentationWarning(250.0, true, 12, MinimumSurfacePoints - 1);
  EXPECT_TRUE(Contains(few, "threshold 250 on an 8-bit volume kept")) << few;
  EXPECT_TRUE(Contains(few, std::to_string(MinimumSurfacePoints - 1) + " points")) << few;
  EXPECT_TRUE(Contains(few, "too little for a vessel")) << few;
  // No surface at all: the mask's voxels are named.
  const std::string none = SegmentationWarning(187.125, false, 7, -1);
  EXPECT_TRUE(Contains(none, "threshold 187.125 on this volume kept 7 voxels and no surface"))
    << none;
  EXPECT_EQ(few.find('\n'), std::string::npos) << "one line";
  // What to do is each front end's to say: the sentence names neither the window nor a flag.
  EXPECT_FALSE(Contains(few, "panel")) << few;
  EXPECT_FALSE(Contains(few, "histogram")) << few;
  EXPECT_FALSE(Contains(few, "--")) << few;
}

TEST(SegmentationWarning, EightBitMeansIntegersFrom0To255)
{
  Volume volume = BallVolume(4, 1.0);
  EXPECT_FALSE(IsEightBit(volume)) << "the ball is 400";
  for (float& v : volume.voxels)
    v *= 0.5f; // 50 and 200
  EXPECT_TRUE(IsEightBit(volume));
  volume.voxels[0] = std::numeric_limits<float>::quiet_NaN(); // not finite: not counted
  EXPECT_TRUE(IsEightBit(volume));
  volume.voxels[1] = 255.5f;
  EXPECT_FALSE(IsEightBit(volume));
  volume.voxels[1] = 256.0f;
  EXPECT_FALSE(IsEightBit(volume));
  volume.voxels[1] = -1.0f;
  EXPECT_FALSE(IsEightBit(volume));
  Volume empty;
  EXPECT_FALSE(IsEightBit(empty));
}

TEST(SegmentLoadedVolume, TheResultCarriesTheRuleOfItsOwnSurface)
{
  SegmentationParameters segmentation;
  segmentation.lower = 250.0;
  SurfaceParameters surface;
  for (const double radius : { 2.5, 11.0 })
  {
    const Volume volume = BallVolume(32, radius);
    const SegmentVolumeResult result = SegmentLoadedVolume(volume, segmentation, surface);
    ASSERT_TRUE(result.mask);
    ASSERT_TRUE(result.surface);
    // The mask kept the ball, the warning is the rule applied to this very result.
    const auto points = static_cast<long long>(result.surface->GetNumberOfPoints());
    EXPECT_GT(result.mask->CountInside(), 0u);
    EXPECT_EQ(result.warning,
      SegmentationWarning(250.0, IsEightBit(volume), result.mask->CountInside(), points));
    ASSERT_FALSE(result.timings.empty());
    EXPECT_EQ(result.timings.front().stage, "segmentation");
    if (radius < 3.0)
    {
      EXPECT_FALSE(result.warning.empty()) << points << " points for a ball of 2.5 voxels";
    }
  }
}

TEST(SegmentDemoVesselOrFallBack, AFailedSegmentationFallsBackToTheVesselItself)
{
  const std::string vessel = std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl";
  ASSERT_TRUE(std::ifstream(vessel).good()) << vessel << " missing: run scripts/fetch-data";
  DemoOptions bad;
  bad.spacing = 5.0; // outside the phantom's range: its parameters are refused
  const DemoVessel demo = SegmentDemoVesselOrFallBack(vessel, bad);
  EXPECT_FALSE(demo.fallback.empty());
  EXPECT_TRUE(demo.volume.voxels.empty());
  ASSERT_TRUE(demo.surface);
  EXPECT_EQ(demo.surface->GetNumberOfPoints(), ReadMesh(vessel)->GetNumberOfPoints());
  // Nothing to fall back to: the reader's error.
  EXPECT_THROW(SegmentDemoVesselOrFallBack("/nonexistent/vessel.stl", bad), std::exception);
}
