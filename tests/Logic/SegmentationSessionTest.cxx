// The segmentation half of the application state: the loaded volume, parameters validated
// when set, the segment job run on another thread and finished on the session's, stale jobs.
#include "SegmentationSession.h"

#include "VolumeIO.h"

#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <thread>

using namespace bender;

namespace
{

// 32^3 voxels of 1 mm, background 100, a bright tube (400) of radius 5 along x.
std::shared_ptr<const Volume> TubeVolume()
{
  auto volume = std::make_shared<Volume>();
  volume->geometry.size = { 32, 32, 32 };
  volume->voxels.assign(volume->geometry.VoxelCount(), 100.0f);
  for (std::size_t k = 0; k < 32; ++k)
    for (std::size_t j = 0; j < 32; ++j)
      for (std::size_t i = 3; i < 29; ++i)
      {
        const double y = double(j) - 15.5, z = double(k) - 15.5;
        if (std::sqrt(y * y + z * z) < 5.0)
          volume->voxels[volume->geometry.LinearIndex(i, j, k)] = 400.0f;
      }
  return volume;
}

}

TEST(SegmentationSession, RefusesWithoutAVolumeAndValidatesSettings)
{
  SegmentationSession session;
  std::string problem;
  EXPECT_FALSE(session.BeginSegment(problem));
  EXPECT_NE(problem.find("open a volume"), std::string::npos) << problem;

  SegmentationSettings bad;
  bad.segmentation.lower = 500.0;
  bad.segmentation.upper = 200.0; // an empty window
  problem.clear();
  EXPECT_FALSE(session.SetSettings(bad, problem));
  EXPECT_FALSE(problem.empty());
  EXPECT_EQ(session.GetSettings().segmentation.lower, SegmentationSettings{}.segmentation.lower);
  SegmentationSettings smoothing;
  smoothing.surface.smoothing = 1.5;
  EXPECT_FALSE(session.SetSettings(smoothing, problem));
}

TEST(SegmentationSession, SegmentJobRunsOnAnotherThreadAndKeepsTheMask)
{
  SegmentationSession session;
  session.SetVolume(TubeVolume(), "tube.nrrd");
  ASSERT_TRUE(session.HasVolume());
  EXPECT_FALSE(session.GetMask());
  std::string problem;
  SegmentationSettings settings;
  settings.segmentation.lower = 250.0;
  ASSERT_TRUE(session.SetSettings(settings, problem)) << problem;
  auto job = session.BeginSegment(problem);
  ASSERT_TRUE(job) << problem;
  std::thread worker([job]() { job->Run({}); });
  worker.join();
  ASSERT_TRUE(job->mask);
  ASSERT_TRUE(job->surface);
  EXPECT_GT(job->surface->GetNumberOfPolys(), 100);
  // About the tube's voxels (pi 5^2 x 26 = 2042), none of the background.
  const std::size_t inside = job->mask->CountInside();
  EXPECT_GT(inside, 1500u);
  EXPECT_LT(inside, 2600u);
  session.FinishSegment(*job);
  EXPECT_EQ(session.GetMask(), job->mask);

  // A job for a volume that is no longer loaded leaves the new volume's (absent) mask alone.
  auto stale = session.BeginSegment(problem);
  ASSERT_TRUE(stale);
  stale->Run({});
  session.SetVolume(TubeVolume(), "other.nrrd");
  session.FinishSegment(*stale);
  EXPECT_FALSE(session.GetMask());
  session.Clear();
  EXPECT_FALSE(session.HasVolume());
}

TEST(SegmentationSession, AVolumeIsReadWithItsMaskAndRemembersItsFile)
{
  // A recovered session reads the volume and the mask of its segmentation kept beside it.
  std::random_device random;
  const std::filesystem::path folder = std::filesystem::temp_directory_path() /
    ("bender-segmentation-session-" + std::to_string(random()));
  std::filesystem::create_directories(folder);
  const std::string volumePath = (folder / "tube.nrrd").string();
  const std::string maskPath = (folder / "tube-mask.nrrd").string();
  WriteVolume(*TubeVolume(), volumePath);

  SegmentationSession session;
  session.SetVolume(TubeVolume(), "tube");
  std::string problem;
  auto segment = session.BeginSegment(problem);
  ASSERT_TRUE(segment) << problem;
  segment->Run({});
  WriteLabelMap(*segment->mask, maskPath);

  auto read = session.BeginRead(volumePath);
  read->maskPath = maskPath;
  read->Run({});
  ASSERT_TRUE(read->volume);
  ASSERT_TRUE(read->mask) << read->maskProblem;
  EXPECT_TRUE(read->maskProblem.empty());
  EXPECT_EQ(read->mask->voxels, segment->mask->voxels);
  session.FinishRead(*read, "tube (recovered)");
  EXPECT_EQ(session.GetVolume(), read->volume);
  EXPECT_EQ(session.GetMask(), read->mask);
  EXPECT_EQ(session.GetVolumeName(), "tube (recovered)");
  EXPECT_EQ(std::filesystem::path(session.GetVolumeSource().path),
    std::filesystem::absolute(volumePath).lexically_normal());

  // A mask on another grid, or none at all: the volume is read, the mask is not, and why.
  auto other = std::make_shared<Volume>(*TubeVolume());
  other->geometry.spacing = { 0.5, 0.5, 0.5 };
  other->geometry.size = { 16, 16, 16 };
  other->voxels.assign(other->geometry.VoxelCount(), 0.0f);
  const std::string wrongMask = (folder / "other-mask.nrrd").string();
  WriteVolume(*other, wrongMask);
  auto wrong = session.BeginRead(volumePath);
  wrong->maskPath = wrongMask;
  wrong->Run({});
  EXPECT_TRUE(wrong->volume);
  EXPECT_FALSE(wrong->mask);
  EXPECT_NE(wrong->maskProblem.find("other-mask.nrrd: the mask is not on the volume's grid"),
    std::string::npos)
    << wrong->maskProblem;
  auto missing = session.BeginRead(volumePath);
  missing->maskPath = (folder / "gone.nrrd").string();
  missing->Run({});
  EXPECT_TRUE(missing->volume);
  EXPECT_FALSE(missing->mask);
  EXPECT_NE(missing->maskProblem.find("gone.nrrd"), std::string::npos) << missing->maskProblem;
  session.FinishRead(*missing);
  EXPECT_FALSE(session.GetMask());
  EXPECT_EQ(session.GetVolumeName(), "tube.nrrd");

  std::error_code ec;
  std::filesystem::remove_all(folder, ec);
}
