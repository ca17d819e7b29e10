// Both extractors: closed, outward, accurate, in LPS for oblique and left-handed grids; the
// module's windowed-sinc smoothing against vtkWindowedSincPolyDataFilter.
#include "SegmentationTestUtilities.h"

#include "SegmentationErrors.h"
#include "SurfaceExtraction.h"
#include "SurfaceMetrics.h"

#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <algorithm>
#include <atomic>
#include <cmath>

namespace
{

using bender::Point3;

bender::LabelMap BallMask(const bender::ImageGeometry& g,
  const std::vector<std::pair<Point3, double>>& balls)
{
  bender::LabelMap mask;
  mask.geometry = g;
  mask.voxels.assign(g.VoxelCount(), 0);
  for (std::size_t k = 0; k < g.size[2]; ++k)
    for (std::size_t j = 0; j < g.size[1]; ++j)
      for (std::size_t i = 0; i < g.size[0]; ++i)
      {
        const Point3 p = g.IndexToPhysical({ { double(i), double(j), double(k) } });
        for (const auto& b : balls)
        {
          if (std::hypot(p[0] - b.first[0], p[1] - b.first[1], p[2] - b.first[2]) <= b.second)
          {
            mask.voxels[g.LinearIndex(i, j, k)] = 1;
          }
        }
      }
  return mask;
}

struct SphereFit
{
  Point3 centroid{ { 0, 0, 0 } };
  double meanRadiusError = 0.0;
  double outwardFraction = 0.0;
};

SphereFit Fit(vtkPolyData* surface, const Point3& centre, double radius)
{
  SphereFit fit;
  vtkDataArray* normals = surface->GetPointData()->GetNormals();
  EXPECT_NE(normals, nullptr);
  const vtkIdType n = surface->GetNumberOfPoints();
  std::size_t outward = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    surface->GetPoint(i, p);
    const double d[3] = { p[0] - centre[0], p[1] - centre[1], p[2] - centre[2] };
    const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    fit.meanRadiusError += std::abs(r - radius) / double(n);
    for (int c = 0; c < 3; ++c)
    {
      fit.centroid[c] += p[c] / double(n);
    }
    if (normals)
    {
      double nn[3];
      normals->GetTuple(i, nn);
      outward += (nn[0] * d[0] + nn[1] * d[1] + nn[2] * d[2]) > 0.0 ? 1 : 0;
    }
  }
  fit.outwardFraction = double(outward) / double(n);
  return fit;
}

class BothExtractors : public ::testing::TestWithParam<bender::SurfaceExtractor>
{
};

TEST_P(BothExtractors, SphereIsClosedOutwardAndAccurate)
{
  const Point3 centre{ { 9.0, 10.0, 11.0 } };
  const bender::LabelMap mask = BallMask(bender_test::CubeGeometry(44, 0.5), { { centre, 6.0 } });
  bender::SurfaceParameters p;
  p.extractor = GetParam();
  const bender::SurfaceResult result = bender::ExtractSurface(mask, p);
  EXPECT_EQ(result.boundaryEdges, 0u);
  EXPECT_EQ(result.nonManifoldEdges, 0u);
  const SphereFit fit = Fit(result.surface, centre, 6.0);
  EXPECT_GT(fit.outwardFraction, 0.99);
  EXPECT_LT(fit.meanRadiusError, 0.25 * 0.5) << "mean radius error, mm";
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(fit.centroid[c], centre[c], 0.05);
  }
  // The raw staircase (smoothing 0) is further from the sphere than the smoothed surface.
  p.smoothing = 0.0;
  const SphereFit raw = Fit(bender::ExtractSurface(mask, p).surface, centre, 6.0);
  EXPECT_GT(raw.meanRadiusError, fit.meanRadiusError);
  EXPECT_FALSE(result.timings.empty());
}

TEST_P(BothExtractors, ObliqueLeftHandedGridGivesTheLpsSphereWithOutwardNormals)
{
  bender::ImageGeometry g = bender_test::CubeGeometry(40, 0.5, { { 100.0, -50.0, 20.0 } });
  g.direction = bender_test::ObliqueDirection();
  // Flip the third axis: a left-handed grid, as many DICOM/NIfTI files have.
  for (int r = 0; r < 3; ++r)
  {
    g.direction[3 * r + 2] = -g.direction[3 * r + 2];
  }
  const Point3 centre = g.IndexToPhysical({ { 20.0, 19.0, 21.0 } });
  const bender::LabelMap mask = BallMask(g, { { centre, 5.0 } });
  bender::SurfaceParameters p;
  p.extractor = GetParam();
  const bender::SurfaceResult result = bender::ExtractSurface(mask, p);
  EXPECT_EQ(result.boundaryEdges, 0u);
  const SphereFit fit = Fit(result.surface, centre, 5.0);
  EXPECT_GT(fit.outwardFraction, 0.99);
  EXPECT_LT(fit.meanRadiusError, 0.15);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(fit.centroid[c], centre[c], 0.05);
  }
}

TEST_P(BothExtractors, LumenTouchingTheVolumeBorderStillGivesAClosedSurface)
{
  const bender::LabelMap mask =
    BallMask(bender_test::CubeGeometry(20, 0.5), { { { { 0.0, 4.5, 4.5 } }, 3.0 } });
  bender::SurfaceParameters p;
  p.extractor = GetParam();
  EXPECT_EQ(bender::ExtractSurface(mask, p).boundaryEdges, 0u);
}

INSTANTIATE_TEST_SUITE_P(Segmentation,
  BothExtractors,
  ::testing::Values(bender::SurfaceExtractor::Vtk, bender::SurfaceExtractor::Itk),
  [](const ::testing::TestParamInfo<bender::SurfaceExtractor>& info)
  { return info.param == bender::SurfaceExtractor::Vtk ? "Vtk" : "Itk"; });

TEST(SurfaceExtraction, SeedsKeepTheirPieceAndTheDefaultKeepsTheLargest)
{
  const Point3 small{ { 5.0, 5.0, 5.0 } };
  const Point3 large{ { 14.0, 14.0, 14.0 } };
  const bender::LabelMap mask =
    BallMask(bender_test::CubeGeometry(40, 0.5), { { small, 2.5 }, { large, 4.0 } });
  bender::SurfaceParameters p;
  const SphereFit largest = Fit(bender::ExtractSurface(mask, p).surface, large, 4.0);
  EXPECT_LT(largest.meanRadiusError, 0.2);
  p.seeds = { small };
  const SphereFit seeded = Fit(bender::ExtractSurface(mask, p).surface, small, 2.5);
  EXPECT_LT(seeded.meanRadiusError, 0.2);
  p.seeds = { small, large };
  const bender::SurfaceResult both = bender::ExtractSurface(mask, p);
  double bounds[6];
  both.surface->GetBounds(bounds);
  EXPECT_NEAR(bounds[0], small[0] - 2.5, 0.5);
  EXPECT_NEAR(bounds[1], large[0] + 4.0, 0.5);
}

TEST(SurfaceExtraction, DecimationReachesTheTargetAndKeepsTheShape)
{
  const Point3 centre{ { 10.0, 10.0, 10.0 } };
  const bender::LabelMap mask = BallMask(bender_test::CubeGeometry(44, 0.5), { { centre, 7.0 } });
  bender::SurfaceParameters p;
  p.targetTriangles = 2000;
  const bender::SurfaceResult result = bender::ExtractSurface(mask, p);
  EXPECT_NEAR(double(result.surface->GetNumberOfPolys()), 2000.0, 200.0);
  EXPECT_EQ(result.boundaryEdges, 0u);
  const SphereFit fit = Fit(result.surface, centre, 7.0);
  EXPECT_LT(fit.meanRadiusError, 0.2);
  EXPECT_GT(fit.outwardFraction, 0.99);
  const bender::TriangleQuality quality = bender::MeasureTriangleQuality(result.surface);
  EXPECT_EQ(quality.triangles, std::size_t(result.surface->GetNumberOfPolys()));
  EXPECT_GT(quality.meanMinAngle, 20.0);
}

TEST(SurfaceExtraction, SmoothingMatchesVtkWindowedSinc)
{
  // Two touching balls of different sizes on an anisotropic grid: a closed surface with a neck.
  bender::ImageGeometry g = bender_test::CubeGeometry(40, 0.5, { { 3.0, -2.0, 1.0 } });
  g.spacing = { { 0.5, 0.45, 0.6 } };
  const bender::LabelMap mask =
    BallMask(g, { { { { 10.0, 7.0, 11.0 } }, 5.0 }, { { { 16.5, 9.0, 12.0 } }, 3.0 } });
  for (double smoothing : { 0.25, 0.5, 1.0 })
  {
    bender::SurfaceParameters raw;
    raw.smoothing = 0.0;
    const bender::SurfaceResult unsmoothed = bender::ExtractSurface(mask, raw);
    bender::SurfaceParameters p;
    p.smoothing = smoothing;
    const bender::SurfaceResult result = bender::ExtractSurface(mask, p);
    ASSERT_EQ(result.surface->GetNumberOfPoints(), unsmoothed.surface->GetNumberOfPoints());
    vtkNew<vtkWindowedSincPolyDataFilter> vtk;
    vtk->SetInputData(unsmoothed.surface);
    vtk->SetNumberOfIterations(20);
    vtk->SetPassBand(std::pow(10.0, -4.0 * smoothing));
    vtk->BoundarySmoothingOff();
    vtk->FeatureEdgeSmoothingOff();
    vtk->NonManifoldSmoothingOn();
    vtk->NormalizeCoordinatesOn();
    vtk->Update();
    double worst = 0.0;
    double moved = 0.0;
    for (vtkIdType i = 0; i < result.surface->GetNumberOfPoints(); ++i)
    {
      double a[3], b[3], c[3];
      result.surface->GetPoint(i, a);
      vtk->GetOutput()->GetPoint(i, b);
      unsmoothed.surface->GetPoint(i, c);
      worst = std::max(worst, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
      moved = std::max(moved, std::hypot(a[0] - c[0], a[1] - c[1], a[2] - c[2]));
    }
    EXPECT_LT(worst, 1e-4) << "smoothing " << smoothing;
    EXPECT_GT(moved, 0.05) << "smoothing " << smoothing;
    EXPECT_EQ(result.boundaryEdges, 0u);
  }
}

TEST(SurfaceExtraction, BadParametersAndCancellation)
{
  const bender::LabelMap mask =
    BallMask(bender_test::CubeGeometry(20, 0.5), { { { { 5, 5, 5 } }, 3.0 } });
  bender::SurfaceParameters p;
  p.smoothing = 1.5;
  EXPECT_THROW(bender::ExtractSurface(mask, p), bender::ParameterError);
  bender::LabelMap empty = mask;
  std::fill(empty.voxels.begin(), empty.voxels.end(), 0);
  EXPECT_THROW(bender::ExtractSurface(empty, {}), bender::ParameterError);
  std::atomic<bool> cancel{ true };
  bender::ProgressReporter progress;
  progress.cancel = &cancel;
  EXPECT_THROW(bender::ExtractSurface(mask, {}, progress), bender::SegmentationCancelled);
}

TEST(SurfaceMetrics, DistanceBetweenConcentricSpheresIsTheirRadiusDifference)
{
  const Point3 centre{ { 10.0, 10.0, 10.0 } };
  const bender::ImageGeometry g = bender_test::CubeGeometry(44, 0.5);
  bender::SurfaceParameters p;
  p.smoothing = 0.8;
  const auto inner = bender::ExtractSurface(BallMask(g, { { centre, 5.0 } }), p).surface;
  const auto outer = bender::ExtractSurface(BallMask(g, { { centre, 7.0 } }), p).surface;
  const bender::SurfaceAccuracy a = bender::MeasureSurfaceAccuracy(inner, outer);
  EXPECT_NEAR(a.toTruth.mean, 2.0, 0.2);
  EXPECT_NEAR(a.fromTruth.mean, 2.0, 0.2);
  EXPECT_GE(a.toTruth.p95, a.toTruth.mean);
  EXPECT_GE(a.toTruth.max, a.toTruth.p95);
  const bender::SurfaceAccuracy self = bender::MeasureSurfaceAccuracy(inner, inner);
  EXPECT_LT(self.toTruth.max, 1e-6);
  // Excluding everything near the inner sphere leaves nothing to measure.
  EXPECT_THROW(bender::MeasureSurfaceAccuracy(inner, outer, inner, 10.0), std::invalid_argument);
}

} // namespace
