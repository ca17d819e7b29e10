// bender-cli render end to end (label rendering; run under xvfb-run where VTK needs X).

#include "CliPostTestUtilities.h"

#include <gtest/gtest.h>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <cstdlib>

using namespace clitest;

namespace
{
struct ImageStats
{
  int width = 0;
  int height = 0;
  double variance = 0.0;       ///< of the grey level, over all pixels
  double covered = 0.0;        ///< fraction of pixels that are not the white background
  double orangeFraction = 0.0; ///< fraction of clearly orange pixels (the final ribbon)
};

ImageStats Measure(const std::string& png)
{
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(png.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  ImageStats stats;
  int dims[3];
  image->GetDimensions(dims);
  stats.width = dims[0];
  stats.height = dims[1];
  const int comps = image->GetNumberOfScalarComponents();
  if (comps < 3 || dims[0] * dims[1] == 0)
  {
    return stats;
  }
  double sum = 0.0, sum2 = 0.0;
  long covered = 0, orange = 0;
  const long n = static_cast<long>(dims[0]) * dims[1];
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      double rgb[3];
      for (int c = 0; c < 3; ++c)
      {
        rgb[c] = image->GetScalarComponentAsDouble(x, y, 0, c);
      }
      const double grey = (rgb[0] + rgb[1] + rgb[2]) / 3.0;
      sum += grey;
      sum2 += grey * grey;
      covered += (rgb[0] < 250 || rgb[1] < 250 || rgb[2] < 250) ? 1 : 0;
      orange += (rgb[0] > 150 && rgb[0] > rgb[2] + 60 && rgb[1] < rgb[0] - 20) ? 1 : 0;
    }
  }
  const double mean = sum / n;
  stats.variance = sum2 / n - mean * mean;
  stats.covered = static_cast<double>(covered) / n;
  stats.orangeFraction = static_cast<double>(orange) / n;
  return stats;
}

class CliRender : public ScratchTest
{
protected:
  void SetUp() override
  {
    ScratchTest::SetUp();
    // VTK 9.1 as packaged here renders through X: without a display it aborts.
    if (!std::getenv("DISPLAY"))
    {
      GTEST_FAIL() << "no DISPLAY: run the rendering tests under xvfb-run -a (scripts/test does)";
    }
  }
};
} // namespace

TEST_F(CliRender, WritesANonBlankPng)
{
  const std::string tube = Data + "/conformance/tube.off";
  const Result r = Run("render " + Q(tube) + " -o " + Q(Tmp("tube.png")) + " --size 320x240");
  ASSERT_EQ(r.status, 0) << r.errors;
  const ImageStats s = Measure(Tmp("tube.png"));
  EXPECT_EQ(s.width, 320);
  EXPECT_EQ(s.height, 240);
  EXPECT_GT(s.variance, 10.0);
  // The camera frames the mesh: it covers a reasonable part of the picture, not all of it.
  EXPECT_GT(s.covered, 0.05);
  EXPECT_LT(s.covered, 0.9);
  EXPECT_EQ(Files(), std::vector<std::string>{ "tube.png" }) << "no temporary left";
}

TEST_F(CliRender, EveryViewAndWireframe)
{
  const std::string tube = Data + "/conformance/tube.off";
  for (const char* view : { "iso", "front", "back", "left", "right", "top", "bottom" })
  {
    const std::string png = Tmp(std::string(view) + ".png");
    const Result r =
      Run("render " + Q(tube) + " -o " + Q(png) + " --size 160x120 --wireframe --view " + view);
    ASSERT_EQ(r.status, 0) << view << ": " << r.errors;
    const ImageStats s = Measure(png);
    EXPECT_GT(s.variance, 10.0) << view;
    EXPECT_GT(s.covered, 0.02) << view;
  }
}

TEST_F(CliRender, ShowsThePlanRibbons)
{
  const std::string tube = Data + "/conformance/tube.off";
  const std::string plan = Examples + "fig14-tube-bend.bender.json";
  Result r = Run("render " + Q(tube) + " -o " + Q(Tmp("plain.png")) + " --size 320x240");
  ASSERT_EQ(r.status, 0) << r.errors;
  r = Run("render " + Q(tube) + " -o " + Q(Tmp("ribbon.png")) + " --size 320x240 --plan " +
    Q(plan) + " --show-ribbon");
  ASSERT_EQ(r.status, 0) << r.errors;
  const ImageStats plain = Measure(Tmp("plain.png"));
  const ImageStats ribbon = Measure(Tmp("ribbon.png"));
  EXPECT_EQ(plain.orangeFraction, 0.0);
  EXPECT_GT(ribbon.orangeFraction, 0.0005) << "the final ribbon is drawn orange";
}

TEST_F(CliRender, BadInputFailsWithoutWriting)
{
  Result r = Run("render " + Q(Data + "/cli/truncated.stl") + " -o " + Q(Tmp("x.png")));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.errors.find("truncated.stl"), std::string::npos) << r.errors;
  r = Run(
    "render " + Q(Data + "/conformance/tube.off") + " -o " + Q(Tmp("x.png")) + " --view sideways");
  EXPECT_EQ(r.status, 2);
  r = Run(
    "render " + Q(Data + "/conformance/tube.off") + " -o " + Q(Tmp("x.png")) + " --show-ribbon");
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Files().empty());
}
