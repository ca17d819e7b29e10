// End to end on real anatomy: the aneurysm phantom (accuracy bound of the default pipeline, both
// extractors, vesselness), the Colin27 head MRI (orientation, ~1 M triangles) and bender-cli.
#include "SegmentationTestUtilities.h"

#include "MeshIO.h"
#include "SegmentCommand.h"
#include "SurfaceMetrics.h"
#include "VesselPhantom.h"

#include <vtkPolyData.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <sys/wait.h>

namespace
{

class AneurysmPhantom : public ::testing::Test
{
protected:
  static void SetUpTestSuite()
  {
    Truth = bender::ReadMesh(bender_test::ExternalData("aneurysm_data.stl"));
    Built = bender::MakeVesselPhantom(Truth, Parameters);
  }
  static void TearDownTestSuite()
  {
    Truth = nullptr;
    Built = bender::Phantom{};
  }
  static bender::SurfaceAccuracy Accuracy(vtkPolyData* surface)
  {
    // Against the open STL; vertices within 1 mm of the caps (cut vessel ends) are left out.
    return bender::MeasureSurfaceAccuracy(surface, Truth, Built.caps, 1.0);
  }
  static inline bender::PhantomParameters Parameters{};
  static inline vtkSmartPointer<vtkPolyData> Truth;
  static inline bender::Phantom Built;
};

TEST_F(AneurysmPhantom, HasMraLikeContrastAndThreeCappedEnds)
{
  const bender::ImageGeometry& g = Built.volume.geometry;
  EXPECT_DOUBLE_EQ(g.spacing[0], 0.4);
  EXPECT_GT(g.VoxelCount(), 1000000u);
  EXPECT_EQ(Built.vesselSeeds.size(), 3u);
  EXPECT_EQ(Built.caps->GetNumberOfPolys() > 0, true);
  const bender::Point3 ci = g.PhysicalToIndex(Built.seed);
  const float lumen = Built.volume.voxels[g.LinearIndex(std::size_t(std::lround(ci[0])),
    std::size_t(std::lround(ci[1])),
    std::size_t(std::lround(ci[2])))];
  EXPECT_NEAR(lumen, 400.0, 80.0);
  EXPECT_NEAR(Built.volume.voxels[0], 100.0, 60.0);
  // Deterministic: the same parameters give the same voxels.
  bender::PhantomParameters coarse;
  coarse.spacing = 1.0;
  EXPECT_EQ(bender::MakeVesselPhantom(Truth, coarse).volume.voxels,
    bender::MakeVesselPhantom(Truth, coarse).volume.voxels);
}

class PhantomExtractors
  : public AneurysmPhantom
  , public ::testing::WithParamInterface<bender::SurfaceExtractor>
{
};

TEST_P(PhantomExtractors, DefaultPipelineIsWithinHalfAVoxel)
{
  bender::SegmentationParameters segmentation;
  segmentation.seeds = { Built.seed };
  const bender::LabelMap mask = bender::SegmentVessels(Built.volume, segmentation);
  bender::SurfaceParameters surface;
  surface.extractor = GetParam();
  surface.seeds = segmentation.seeds;
  const bender::SurfaceResult result = bender::ExtractSurface(mask, surface);
  EXPECT_EQ(result.boundaryEdges, 0u);
  EXPECT_EQ(result.nonManifoldEdges, 0u);
  const bender::SurfaceAccuracy a = Accuracy(result.surface);
  const bender::TriangleQuality q = bender::MeasureTriangleQuality(result.surface);
  std::cout << "[ phantom  ] extractor "
            << (GetParam() == bender::SurfaceExtractor::Vtk ? "vtk" : "itk") << ": "
            << result.surface->GetNumberOfPolys() << " triangles; to truth mean " << a.toTruth.mean
            << " p95 " << a.toTruth.p95 << "; from truth mean " << a.fromTruth.mean << " p95 "
            << a.fromTruth.p95 << " mm; min angle mean " << q.meanMinAngle << " deg, <10 deg "
            << 100.0 * q.fractionBelow10Deg << "%\n";
  const double halfVoxel = 0.5 * Parameters.spacing;
  EXPECT_LT(a.toTruth.mean, halfVoxel);
  EXPECT_LT(a.fromTruth.mean, halfVoxel);
  EXPECT_LT(a.toTruth.p95, 2.0 * Parameters.spacing);
  EXPECT_LT(a.fromTruth.p95, 2.0 * Parameters.spacing);
  // Most of the truth is compared: the exclusion only removes the cut ends.
  EXPECT_GT(double(a.fromTruth.samples), 0.85 * double(Truth->GetNumberOfPoints()));
}

INSTANTIATE_TEST_SUITE_P(Segmentation,
  PhantomExtractors,
  ::testing::Values(bender::SurfaceExtractor::Vtk, bender::SurfaceExtractor::Itk),
  [](const ::testing::TestParamInfo<bender::SurfaceExtractor>& info)
  { return info.param == bender::SurfaceExtractor::Vtk ? "Vtk" : "Itk"; });

TEST_F(AneurysmPhantom, VesselnessSegmentsTheTubularVesselsOnly)
{
  bender::SegmentationParameters p;
  p.method = bender::SegmentationMethod::Vesselness;
  p.scales = 3;
  p.seeds = Built.vesselSeeds;
  const bender::LabelMap vessels = bender::SegmentVessels(Built.volume, p);
  bender::SegmentationParameters threshold;
  threshold.seeds = { Built.seed };
  const std::size_t lumen = bender::SegmentVessels(Built.volume, threshold).CountInside();
  std::size_t bright = 0;
  for (std::size_t n = 0; n < vessels.voxels.size(); ++n)
  {
    bright += (vessels.voxels[n] && Built.volume.voxels[n] > 200.0f) ? 1 : 0;
  }
  EXPECT_GT(double(bright), 0.85 * double(vessels.CountInside()))
    << "vesselness leaks into background";
  EXPECT_GT(double(vessels.CountInside()), 0.15 * double(lumen));
  EXPECT_LT(vessels.CountInside(), lumen) << "the round sac is not a vessel";
}

TEST_F(AneurysmPhantom, SegmentCommandWritesTheSurfaceWithinTheBound)
{
  bender_test::TempDir dir;
  const std::string volume = dir.File("phantom.nrrd");
  bender::WriteVolume(Built.volume, volume);
  std::ostringstream out, err;
  std::ostringstream seed;
  seed << Built.seed[0] << "," << Built.seed[1] << "," << Built.seed[2];
  ASSERT_EQ(bender::RunSegmentCli(
              { volume, "-o", dir.File("lumen.stl"), "--seed", seed.str(), "-q" }, out, err),
    0)
    << err.str();
  EXPECT_NE(out.str().find("closed"), std::string::npos) << out.str();
  const auto surface = bender::ReadMesh(dir.File("lumen.stl"));
  const bender::SurfaceAccuracy a = Accuracy(surface);
  EXPECT_LT(a.toTruth.mean, 0.5 * Parameters.spacing);
  EXPECT_LT(a.fromTruth.mean, 0.5 * Parameters.spacing);

  std::ostringstream out2, err2;
  EXPECT_EQ(
    bender::RunSegmentCli({ volume, "-o", dir.File("x.stl"), "--seed", "500,0,0" }, out2, err2), 1);
  EXPECT_NE(err2.str().find("outside the volume"), std::string::npos) << err2.str();
  EXPECT_FALSE(std::filesystem::exists(dir.File("x.stl")));
  std::ostringstream out3, err3;
  bender::Point3 corner = Built.volume.geometry.IndexToPhysical({ { 1, 1, 1 } });
  const std::string background =
    std::to_string(corner[0]) + "," + std::to_string(corner[1]) + "," + std::to_string(corner[2]);
  EXPECT_EQ(
    bender::RunSegmentCli({ volume, "-o", dir.File("x.stl"), "--seed", background }, out3, err3),
    1);
  EXPECT_NE(err3.str().find("background"), std::string::npos) << err3.str();
}

std::string RunCli(const std::string& arguments, int& status)
{
  const std::string command = std::string(BENDER_CLI_PATH) + " " + arguments + " 2>&1";
  std::FILE* pipe = ::popen(command.c_str(), "r");
  std::string text;
  char buffer[512];
  while (pipe && std::fgets(buffer, sizeof(buffer), pipe))
  {
    text += buffer;
  }
  const int raw = pipe ? ::pclose(pipe) : -1;
  status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return text;
}

TEST(SegmentationCli, PhantomThenSegmentThroughTheExecutable)
{
  ASSERT_TRUE(std::filesystem::exists(BENDER_CLI_PATH)) << BENDER_CLI_PATH;
  bender_test::TempDir dir;
  int status = 0;
  std::string text = RunCli("phantom --help", status);
  EXPECT_EQ(status, 0);
  EXPECT_NE(text.find("usage: bender-cli phantom"), std::string::npos);
  text = RunCli("segment --help", status);
  EXPECT_EQ(status, 0);
  EXPECT_NE(text.find("--extractor"), std::string::npos);

  text = RunCli("phantom " + bender_test::ExternalData("aneurysm_data.stl") + " -o " +
      dir.File("p.nii.gz") + " --spacing 0.8",
    status);
  ASSERT_EQ(status, 0) << text;
  const std::string marker = "--seed ";
  const std::size_t at = text.find(marker);
  ASSERT_NE(at, std::string::npos) << text;
  const std::string seed =
    text.substr(at + marker.size(), text.find('\n', at) - at - marker.size());
  text = RunCli("segment " + dir.File("p.nii.gz") + " -o " + dir.File("s.vtp") + " --seed " + seed +
      " --extractor itk --target-triangles 5000",
    status);
  ASSERT_EQ(status, 0) << text;
  const auto surface = bender::ReadMesh(dir.File("s.vtp"));
  EXPECT_NEAR(double(surface->GetNumberOfPolys()), 5000.0, 500.0);

  text = RunCli("segment " + dir.File("missing.nrrd") + " -o " + dir.File("t.stl"), status);
  EXPECT_EQ(status, 1);
  EXPECT_NE(text.find("missing.nrrd: no such file"), std::string::npos) << text;
  text = RunCli(
    "segment " + dir.File("p.nii.gz") + " -o " + dir.File("t.stl") + " --method blob", status);
  EXPECT_EQ(status, 2);
  EXPECT_NE(text.find("--method"), std::string::npos) << text;
}

TEST(SegmentationCli, ArgumentsAreParsedAndCheckedAgainstTheirRanges)
{
  const bender::SegmentRequest r = bender::ParseSegmentArguments({ "in.nrrd",
    "-o",
    "out.stl",
    "--method",
    "vesselness",
    "--seed",
    "1,2,3",
    "4,5,6",
    "--seed",
    "7,8,9",
    "--lower",
    "10",
    "--upper",
    "20",
    "--smoothing",
    "0.3",
    "--target-triangles",
    "1000",
    "--extractor",
    "itk" });
  EXPECT_EQ(r.segmentation.method, bender::SegmentationMethod::Vesselness);
  ASSERT_EQ(r.segmentation.seeds.size(), 3u);
  EXPECT_EQ(r.segmentation.seeds[1][1], 5.0);
  EXPECT_EQ(r.surface.seeds.size(), 3u);
  EXPECT_EQ(r.surface.extractor, bender::SurfaceExtractor::Itk);
  EXPECT_EQ(r.surface.targetTriangles, 1000u);
  EXPECT_DOUBLE_EQ(r.surface.smoothing, 0.3);
  EXPECT_THROW(bender::ParseSegmentArguments({ "in.nrrd" }), bender::ParameterError);
  EXPECT_THROW(bender::ParseSegmentArguments({ "in.nrrd", "-o", "o.stl", "--seed", "1,2" }),
    bender::ParameterError);
  EXPECT_THROW(bender::ParseSegmentArguments({ "in.nrrd", "-o", "o.stl", "--smoothing", "2" }),
    bender::ParameterError);
  EXPECT_THROW(bender::ParseSegmentArguments({ "in.nrrd", "-o", "o.stl", "--lower", "x" }),
    bender::ParameterError);
  EXPECT_THROW(bender::ParseSegmentArguments({ "in.nrrd", "-o", "o.stl", "--frobnicate" }),
    bender::ParameterError);
  EXPECT_TRUE(bender::ParseSegmentArguments({ "--help" }).help);
}

TEST(HeadMri, Colin27GivesAMillionTriangleHeadInLps)
{
  const bender::Volume ch2 = bender::ReadVolume(bender_test::ExternalData("ch2.nii.gz"));
  bender::SegmentationParameters p;
  p.lower = 40.0;
  const bender::LabelMap head = bender::SegmentVessels(ch2, p);
  const bender::SurfaceResult result = bender::ExtractSurface(head, {});
  const vtkIdType triangles = result.surface->GetNumberOfPolys();
  std::cout << "[ ch2      ] " << triangles << " triangles;";
  for (const auto& t : result.timings)
  {
    std::cout << " " << t.stage << " " << t.seconds << " s";
  }
  std::cout << "\n";
  EXPECT_GT(triangles, 800000);
  EXPECT_LT(triangles, 1600000);
  EXPECT_EQ(result.boundaryEdges, 0u);
  // LPS: anterior is -y, superior is +z. The nose is the most anterior point, near the midline
  // and below the top of the head; the back of the head lies at +y.
  double bounds[6];
  result.surface->GetBounds(bounds);
  vtkIdType nose = 0;
  for (vtkIdType i = 0; i < result.surface->GetNumberOfPoints(); ++i)
  {
    nose = result.surface->GetPoint(i)[1] < result.surface->GetPoint(nose)[1] ? i : nose;
  }
  double tip[3];
  result.surface->GetPoint(nose, tip);
  std::cout << "[ ch2      ] bounds " << bounds[0] << " " << bounds[1] << " " << bounds[2] << " "
            << bounds[3] << " " << bounds[4] << " " << bounds[5] << "; nose " << tip[0] << " "
            << tip[1] << " " << tip[2] << "\n";
  EXPECT_LT(std::abs(tip[0]), 15.0);
  EXPECT_LT(tip[2], bounds[5] - 40.0);
  EXPECT_LT(bounds[2], -60.0);
  EXPECT_GT(bounds[3], 80.0);
}

} // namespace
