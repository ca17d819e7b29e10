#include "VesselSegmentation.h"

#include "Private/ItkImage.h"
#include "Private/VoxelRuns.h"
#include "StringUtil.h"

#include <itkBinaryBallStructuringElement.h>
#include <itkBinaryFillholeImageFilter.h>
#include <itkBinaryMorphologicalClosingImageFilter.h>
#include <itkBinaryThresholdImageFilter.h>
#include <itkExtractImageFilter.h>
#include <itkGeodesicActiveContourLevelSetImageFilter.h>
#include <itkGradientMagnitudeRecursiveGaussianImageFilter.h>
#include <itkHessianToObjectnessMeasureImageFilter.h>
#include <itkMinimumMaximumImageCalculator.h>
#include <itkMultiScaleHessianBasedMeasureImageFilter.h>
#include <itkSigmoidImageFilter.h>
#include <itkSignedMaurerDistanceMapImageFilter.h>
#include <itkSymmetricSecondRankTensor.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

namespace bender
{
namespace
{

using detail::FloatImage;
using detail::MaskImage;
using detail::VoxelBox;

FloatImage::Pointer NormalisedVesselness(FloatImage* input,
  const SegmentationParameters& p,
  const ProgressReporter& progress)
{
  using HessianPixel = itk::SymmetricSecondRankTensor<double, 3>;
  using HessianImage = itk::Image<HessianPixel, 3>;
  using Objectness = itk::HessianToObjectnessMeasureImageFilter<HessianImage, FloatImage>;
  using MultiScale =
    itk::MultiScaleHessianBasedMeasureImageFilter<FloatImage, HessianImage, FloatImage>;

  auto objectness = Objectness::New();
  objectness->SetObjectDimension(1);
  objectness->SetBrightObject(p.brightVessels);
  objectness->SetScaleObjectnessMeasure(false);
  objectness->SetAlpha(p.alpha);
  objectness->SetBeta(p.beta);
  objectness->SetGamma(p.gamma);

  auto multiScale = MultiScale::New();
  multiScale->SetInput(input);
  multiScale->SetHessianToMeasureFilter(objectness);
  multiScale->SetSigmaStepMethodToLogarithmic();
  // A tube of radius r answers best at sigma = r / sqrt(2) (Sato et al.).
  multiScale->SetSigmaMinimum(p.minRadius / std::sqrt(2.0));
  multiScale->SetSigmaMaximum(p.maxRadius / std::sqrt(2.0));
  multiScale->SetNumberOfSigmaSteps(static_cast<unsigned>(p.scales));
  multiScale->SetNonNegativeHessianBasedMeasure(true);
  detail::WatchFilter(multiScale, progress, "vesselness");
  multiScale->Update();

  FloatImage::Pointer vesselness = multiScale->GetOutput();
  vesselness->DisconnectPipeline();
  float* buffer = vesselness->GetBufferPointer();
  const std::size_t n = vesselness->GetBufferedRegion().GetNumberOfPixels();
  const float maximum = *std::max_element(buffer, buffer + n);
  if (maximum > 0.0f)
  {
    std::transform(buffer, buffer + n, buffer, [maximum](float v) { return v / maximum; });
  }
  return vesselness;
}

/// Face-connected scan-line flood fill on a raw buffer of `size` voxels, limited to `box`:
/// starting from `seeds`, marks every voxel for which fillable(linear index) holds and that is
/// face-connected to a seed through such voxels, by calling mark(linear index) (which must make
/// fillable() false). Touches only the filled voxels and their neighbours, not the whole volume.
/// Returns the bounding box of the marked voxels. Reports progress (fraction of the box marked)
/// and honours cancellation about every million voxels.
template<typename Fillable, typename Mark>
VoxelBox ScanlineFill(const std::array<std::size_t, 3>& size,
  const VoxelBox& box,
  std::vector<std::array<long, 3>> seeds,
  Fillable fillable,
  Mark mark,
  const ProgressReporter& progress,
  const std::string& stage)
{
  VoxelBox filled;
  filled.lo = box.hi;
  filled.hi = box.lo;
  for (int c = 0; c < 3; ++c)
  {
    --filled.hi[c];
  }
  const auto rowStart = [&size](long j, long k) {
    return static_cast<std::size_t>(j) * size[0] + static_cast<std::size_t>(k) * size[0] * size[1];
  };
  const double boxVoxels = double(box.hi[0] - box.lo[0] + 1) * double(box.hi[1] - box.lo[1] + 1) *
    double(box.hi[2] - box.lo[2] + 1);
  std::size_t marked = 0;
  std::size_t nextReport = 1u << 20;
  progress.Report(stage, 0.0);
  progress.ThrowIfCancelled(stage);
  std::vector<std::array<long, 3>>& stack = seeds;
  while (!stack.empty())
  {
    const std::array<long, 3> s = stack.back();
    stack.pop_back();
    const std::size_t row = rowStart(s[1], s[2]);
    if (!fillable(row + std::size_t(s[0])))
    {
      continue;
    }
    long a = s[0];
    long b = s[0];
    while (a > box.lo[0] && fillable(row + std::size_t(a - 1)))
    {
      --a;
    }
    while (b < box.hi[0] && fillable(row + std::size_t(b + 1)))
    {
      ++b;
    }
    for (long x = a; x <= b; ++x)
    {
      mark(row + std::size_t(x));
    }
    marked += std::size_t(b - a + 1);
    filled.lo[0] = std::min(filled.lo[0], a);
    filled.hi[0] = std::max(filled.hi[0], b);
    filled.lo[1] = std::min(filled.lo[1], s[1]);
    filled.hi[1] = std::max(filled.hi[1], s[1]);
    filled.lo[2] = std::min(filled.lo[2], s[2]);
    filled.hi[2] = std::max(filled.hi[2], s[2]);
    const long neighbours[4][2] = {
      { s[1] - 1, s[2] }, { s[1] + 1, s[2] }, { s[1], s[2] - 1 }, { s[1], s[2] + 1 }
    };
    for (const auto& n : neighbours)
    {
      if (n[0] < box.lo[1] || n[0] > box.hi[1] || n[1] < box.lo[2] || n[1] > box.hi[2])
      {
        continue;
      }
      const std::size_t other = rowStart(n[0], n[1]);
      bool inRun = false;
      for (long x = a; x <= b; ++x)
      {
        if (fillable(other + std::size_t(x)))
        {
          if (!inRun)
          {
            stack.push_back({ { x, n[0], n[1] } });
            inRun = true;
          }
        }
        else
        {
          inRun = false;
        }
      }
    }
    if (marked >= nextReport)
    {
      nextReport = marked + (1u << 20);
      progress.Report(stage, std::min(1.0, double(marked) / boxVoxels));
      progress.ThrowIfCancelled(stage);
    }
  }
  progress.Report(stage, 1.0);
  return filled;
}

MaskImage::Pointer RefineWithLevelSet(FloatImage* intensity,
  MaskImage* mask,
  const SegmentationParameters& p,
  const ProgressReporter& progress)
{
  auto distance = itk::SignedMaurerDistanceMapImageFilter<MaskImage, FloatImage>::New();
  distance->SetInput(mask);
  distance->SetInsideIsPositive(false);
  distance->SetSquaredDistance(false);
  distance->SetUseImageSpacing(true);

  auto gradient = itk::GradientMagnitudeRecursiveGaussianImageFilter<FloatImage, FloatImage>::New();
  gradient->SetInput(intensity);
  gradient->SetSigma(p.levelSetSigma);
  gradient->Update();
  auto range = itk::MinimumMaximumImageCalculator<FloatImage>::New();
  range->SetImage(gradient->GetOutput());
  range->ComputeMaximum();
  const double maxGradient = std::max<double>(range->GetMaximum(), 1e-6);
  // Edge potential: ~1 in flat regions, ~0 on edges stronger than a quarter of the strongest.
  auto sigmoid = itk::SigmoidImageFilter<FloatImage, FloatImage>::New();
  sigmoid->SetInput(gradient->GetOutput());
  sigmoid->SetOutputMinimum(0.0f);
  sigmoid->SetOutputMaximum(1.0f);
  sigmoid->SetAlpha(-0.05 * maxGradient);
  sigmoid->SetBeta(0.25 * maxGradient);

  using Contour = itk::GeodesicActiveContourLevelSetImageFilter<FloatImage, FloatImage>;
  auto contour = Contour::New();
  contour->SetInput(distance->GetOutput());
  contour->SetFeatureImage(sigmoid->GetOutput());
  contour->SetPropagationScaling(p.levelSetPropagation);
  contour->SetCurvatureScaling(p.levelSetCurvature);
  contour->SetAdvectionScaling(1.0);
  contour->SetMaximumRMSError(0.002);
  contour->SetNumberOfIterations(static_cast<unsigned>(p.levelSetIterations));
  detail::WatchFilter(contour, progress, "level set");

  auto inside = itk::BinaryThresholdImageFilter<FloatImage, MaskImage>::New();
  inside->SetInput(contour->GetOutput());
  inside->SetLowerThreshold(-std::numeric_limits<float>::max());
  inside->SetUpperThreshold(0.0f);
  inside->SetInsideValue(1);
  inside->SetOutsideValue(0);
  inside->Update();
  MaskImage::Pointer refined = inside->GetOutput();
  refined->DisconnectPipeline();
  return refined;
}

template<typename TImage>
typename TImage::Pointer Crop(TImage* image, const typename TImage::RegionType& region)
{
  auto extract = itk::ExtractImageFilter<TImage, TImage>::New();
  extract->SetInput(image);
  extract->SetExtractionRegion(region);
  extract->SetDirectionCollapseToIdentity();
  extract->Update();
  typename TImage::Pointer out = extract->GetOutput();
  out->DisconnectPipeline();
  return out;
}

LabelMap Segment(const Volume& volume,
  const SegmentationParameters& p,
  const ProgressReporter& progress)
{
  FloatImage::Pointer input = detail::WrapVolume(volume);
  FloatImage::Pointer source = input;
  double lower = p.lower;
  double upper = p.upper;
  std::string quantity = "intensity";
  if (p.method == SegmentationMethod::Vesselness)
  {
    source = NormalisedVesselness(input, p, progress);
    lower = p.vesselnessThreshold;
    upper = std::numeric_limits<double>::max();
    quantity = "vesselness";
  }
  progress.ThrowIfCancelled("segmentation");

  const ImageGeometry& g = volume.geometry;
  LabelMap result;
  result.geometry = g;
  VoxelBox found;
  const float lo = static_cast<float>(std::max<double>(lower, -std::numeric_limits<float>::max()));
  const float hi = static_cast<float>(std::min<double>(upper, std::numeric_limits<float>::max()));
  if (!p.seeds.empty())
  {
    std::vector<std::array<long, 3>> seeds;
    for (const Point3& seed : p.seeds)
    {
      if (!g.ContainsPhysical(seed))
      {
        const Point3 a = g.IndexToPhysical({ { 0, 0, 0 } });
        const Point3 b = g.IndexToPhysical(
          { { double(g.size[0] - 1), double(g.size[1] - 1), double(g.size[2] - 1) } });
        throw SeedError("seed " + FormatPoint(seed) +
          " mm (LPS) is outside the volume, whose voxel centres run from " + FormatPoint(a) +
          " to " + FormatPoint(b));
      }
      const Point3 ci = g.PhysicalToIndex(seed);
      FloatImage::IndexType index;
      for (unsigned c = 0; c < 3; ++c)
      {
        index[c] = std::clamp<long>(std::lround(ci[c]), 0, static_cast<long>(g.size[c]) - 1);
      }
      const double value = source->GetPixel(index);
      if (!(value >= lower && value <= upper))
      {
        std::ostringstream msg;
        msg << "seed " << FormatPoint(seed) << " mm (LPS), voxel (" << index[0] << ", " << index[1]
            << ", " << index[2] << "), is in background: " << quantity << " " << value
            << " is outside [" << lower << ", "
            << (upper >= 1e30 ? std::string("inf") : std::to_string(upper)) << "]";
        throw SeedError(msg.str());
      }
      seeds.push_back({ { index[0], index[1], index[2] } });
    }
    // Seeded region growing (face connectivity, as itk::ConnectedThresholdImageFilter): a
    // scan-line flood fill that touches only the region and its neighbours, not all voxels.
    const float* values = source->GetBufferPointer();
    result.voxels.assign(g.VoxelCount(), 0);
    std::uint8_t* out = result.voxels.data();
    VoxelBox all;
    for (int c = 0; c < 3; ++c)
    {
      all.lo[c] = 0;
      all.hi[c] = static_cast<long>(g.size[c]) - 1;
    }
    found = ScanlineFill(
      g.size,
      all,
      std::move(seeds),
      [values, out, lo, hi](std::size_t i)
      { return out[i] == 0 && values[i] >= lo && values[i] <= hi; },
      [out](std::size_t i) { out[i] = 1; },
      progress,
      "connected region");
  }
  else
  {
    // The largest component (no seed, e.g. a head MRI): run-based labelling of the window.
    result.voxels.assign(g.VoxelCount(), 0);
    found = detail::LargestComponentInPlace(
      source->GetBufferPointer(), g.size, lo, hi, result.voxels.data(), progress);
  }
  source = nullptr;
  progress.ThrowIfCancelled("segmentation");
  if (found.Empty())
  {
    throw SegmentationError("segmentation is empty: no voxel in the " + quantity + " window");
  }

  // Fill holes, closing and the level set run on the region's bounding box (plus a margin) only.
  std::array<long, 3> closingRadius{ { 0, 0, 0 } };
  VoxelBox box;
  for (int c = 0; c < 3; ++c)
  {
    long pad = 2;
    if (p.closingRadius > 0.0)
    {
      closingRadius[c] = std::max(1L, std::lround(p.closingRadius / g.spacing[c]));
    }
    pad += closingRadius[c];
    if (p.levelSetIterations > 0)
    {
      pad += 3 + std::lround(2.0 * p.levelSetSigma / g.spacing[c]);
    }
    box.lo[c] = std::max(0L, found.lo[c] - pad);
    box.hi[c] = std::min(static_cast<long>(g.size[c]) - 1, found.hi[c] + pad);
  }
  MaskImage::RegionType region;
  for (unsigned c = 0; c < 3; ++c)
  {
    region.SetIndex(c, box.lo[c]);
    region.SetSize(c, static_cast<itk::SizeValueType>(box.hi[c] - box.lo[c] + 1));
  }

  if (p.closingRadius > 0.0 || p.levelSetIterations > 0)
  {
    MaskImage::Pointer work = Crop<MaskImage>(detail::WrapLabelMap(result), region);
    if (p.closingRadius > 0.0)
    {
      using Ball = itk::BinaryBallStructuringElement<unsigned char, 3>;
      Ball ball;
      Ball::SizeType radius;
      for (unsigned c = 0; c < 3; ++c)
      {
        radius[c] = static_cast<itk::SizeValueType>(closingRadius[c]);
      }
      ball.SetRadius(radius);
      ball.CreateStructuringElement();
      auto closing = itk::BinaryMorphologicalClosingImageFilter<MaskImage, MaskImage, Ball>::New();
      closing->SetInput(work);
      closing->SetKernel(ball);
      closing->SetForegroundValue(1);
      detail::WatchFilter(closing, progress, "closing");
      closing->Update();
      work = closing->GetOutput();
      work->DisconnectPipeline();
    }
    if (p.levelSetIterations > 0)
    {
      FloatImage::Pointer intensity = Crop<FloatImage>(input, region);
      work = RefineWithLevelSet(intensity, work, p, progress);
    }
    // Back into the full-size map (everything outside the box is background).
    const unsigned char* src = work->GetBufferPointer();
    const long nx = box.hi[0] - box.lo[0] + 1;
    for (long k = box.lo[2]; k <= box.hi[2]; ++k)
    {
      for (long j = box.lo[1]; j <= box.hi[1]; ++j, src += nx)
      {
        std::copy(src,
          src + nx,
          result.voxels.begin() +
            static_cast<std::ptrdiff_t>(
              g.LinearIndex(std::size_t(box.lo[0]), std::size_t(j), std::size_t(k))));
      }
    }
  }
  progress.ThrowIfCancelled("segmentation");
  if (p.fillHoles)
  {
    detail::FillHolesInPlace(result.voxels.data(), g.size, box, progress);
  }
  progress.ThrowIfCancelled("segmentation");

  bool any = false;
  for (long k = box.lo[2]; k <= box.hi[2] && !any; ++k)
  {
    for (long j = box.lo[1]; j <= box.hi[1] && !any; ++j)
    {
      const std::uint8_t* row = result.voxels.data() +
        g.LinearIndex(std::size_t(box.lo[0]), std::size_t(j), std::size_t(k));
      any =
        std::any_of(row, row + (box.hi[0] - box.lo[0] + 1), [](std::uint8_t v) { return v != 0; });
    }
  }
  if (!any)
  {
    throw SegmentationError("segmentation is empty after refinement");
  }
  return result;
}

} // namespace

LabelMap SegmentVessels(const Volume& volume,
  const SegmentationParameters& parameters,
  const ProgressReporter& progress)
{
  ValidateSegmentationParameters(parameters);
  if (volume.geometry.VoxelCount() == 0 || volume.voxels.size() != volume.geometry.VoxelCount())
  {
    throw ParameterError("segmentation: empty or inconsistent volume");
  }
  try
  {
    return Segment(volume, parameters, progress);
  }
  catch (const itk::ProcessAborted&)
  {
    throw SegmentationCancelled("segmentation cancelled");
  }
  catch (const itk::ExceptionObject& e)
  {
    std::string text = e.GetDescription();
    std::replace(text.begin(), text.end(), '\n', ' ');
    throw SegmentationError("segmentation failed: " + text);
  }
}

Volume ComputeVesselness(const Volume& volume,
  const SegmentationParameters& parameters,
  const ProgressReporter& progress)
{
  ValidateSegmentationParameters(parameters);
  try
  {
    FloatImage::Pointer input = detail::WrapVolume(volume);
    FloatImage::Pointer vesselness = NormalisedVesselness(input, parameters, progress);
    Volume out;
    out.geometry = volume.geometry;
    detail::CopyBuffer(vesselness.GetPointer(), out.voxels);
    return out;
  }
  catch (const itk::ProcessAborted&)
  {
    throw SegmentationCancelled("vesselness cancelled");
  }
  catch (const itk::ExceptionObject& e)
  {
    std::string text = e.GetDescription();
    std::replace(text.begin(), text.end(), '\n', ' ');
    throw SegmentationError("vesselness failed: " + text);
  }
}

} // namespace bender
