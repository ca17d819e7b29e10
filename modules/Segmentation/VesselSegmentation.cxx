#include "VesselSegmentation.h"

#include "Private/ItkImage.h"

#include <itkBinaryBallStructuringElement.h>
#include <itkBinaryFillholeImageFilter.h>
#include <itkBinaryMorphologicalClosingImageFilter.h>
#include <itkBinaryThresholdImageFilter.h>
#include <itkConnectedComponentImageFilter.h>
#include <itkConnectedThresholdImageFilter.h>
#include <itkExtractImageFilter.h>
#include <itkGeodesicActiveContourLevelSetImageFilter.h>
#include <itkGradientMagnitudeRecursiveGaussianImageFilter.h>
#include <itkHessianToObjectnessMeasureImageFilter.h>
#include <itkMinimumMaximumImageCalculator.h>
#include <itkMultiScaleHessianBasedMeasureImageFilter.h>
#include <itkRelabelComponentImageFilter.h>
#include <itkSigmoidImageFilter.h>
#include <itkSignedMaurerDistanceMapImageFilter.h>
#include <itkSymmetricSecondRankTensor.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace bender
{
namespace
{

using detail::FloatImage;
using detail::MaskImage;
using LabelImage = itk::Image<unsigned int, 3>;

std::string Format(const Point3& p)
{
  std::ostringstream s;
  s.precision(4);
  s << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return s.str();
}

void Require(bool ok, const std::string& message)
{
  if (!ok)
  {
    throw ParameterError("segmentation parameter " + message);
  }
}

FloatImage::Pointer NormalisedVesselness(
  FloatImage* input, const SegmentationParameters& p, const ProgressReporter& progress)
{
  using HessianPixel = itk::SymmetricSecondRankTensor<double, 3>;
  using HessianImage = itk::Image<HessianPixel, 3>;
  using Objectness = itk::HessianToObjectnessMeasureImageFilter<HessianImage, FloatImage>;
  using MultiScale = itk::MultiScaleHessianBasedMeasureImageFilter<FloatImage, HessianImage, FloatImage>;

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

MaskImage::Pointer LargestComponent(
  FloatImage* source, double lower, double upper, const ProgressReporter& progress)
{
  auto threshold = itk::BinaryThresholdImageFilter<FloatImage, MaskImage>::New();
  threshold->SetInput(source);
  threshold->SetLowerThreshold(static_cast<float>(lower));
  threshold->SetUpperThreshold(static_cast<float>(std::min<double>(upper, std::numeric_limits<float>::max())));
  threshold->SetInsideValue(1);
  threshold->SetOutsideValue(0);
  auto components = itk::ConnectedComponentImageFilter<MaskImage, LabelImage>::New();
  components->SetInput(threshold->GetOutput());
  detail::WatchFilter(components, progress, "components");
  auto relabel = itk::RelabelComponentImageFilter<LabelImage, LabelImage>::New();
  relabel->SetInput(components->GetOutput());
  auto largest = itk::BinaryThresholdImageFilter<LabelImage, MaskImage>::New();
  largest->SetInput(relabel->GetOutput());
  largest->SetLowerThreshold(1);
  largest->SetUpperThreshold(1);
  largest->SetInsideValue(1);
  largest->SetOutsideValue(0);
  largest->Update();
  MaskImage::Pointer mask = largest->GetOutput();
  mask->DisconnectPipeline();
  return mask;
}

/// The bounding region of the mask's voxels, grown by `pad` voxels and clipped to the image.
MaskImage::RegionType BoundingRegion(const MaskImage* mask, const std::array<long, 3>& pad)
{
  const auto size = mask->GetBufferedRegion().GetSize();
  long lo[3] = { static_cast<long>(size[0]), static_cast<long>(size[1]), static_cast<long>(size[2]) };
  long hi[3] = { -1, -1, -1 };
  const unsigned char* p = mask->GetBufferPointer();
  for (long k = 0; k < static_cast<long>(size[2]); ++k)
  {
    for (long j = 0; j < static_cast<long>(size[1]); ++j)
    {
      const unsigned char* row = p + size[0] * (j + size[1] * k);
      const unsigned char* first = std::find(row, row + size[0], 1);
      if (first == row + size[0])
      {
        continue;
      }
      const long iFirst = static_cast<long>(first - row);
      long iLast = static_cast<long>(size[0]) - 1;
      while (row[iLast] == 0)
      {
        --iLast;
      }
      lo[0] = std::min(lo[0], iFirst);
      hi[0] = std::max(hi[0], iLast);
      lo[1] = std::min(lo[1], j);
      hi[1] = std::max(hi[1], j);
      lo[2] = std::min(lo[2], k);
      hi[2] = std::max(hi[2], k);
    }
  }
  MaskImage::RegionType region;
  for (unsigned c = 0; c < 3; ++c)
  {
    const long a = std::max(0L, lo[c] - pad[c]);
    const long b = std::min(static_cast<long>(size[c]) - 1, hi[c] + pad[c]);
    region.SetIndex(c, a);
    region.SetSize(c, static_cast<itk::SizeValueType>(std::max(0L, b - a + 1)));
  }
  return region;
}

MaskImage::Pointer RefineWithLevelSet(FloatImage* intensity, MaskImage* mask,
  const SegmentationParameters& p, const ProgressReporter& progress)
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

template <typename TImage>
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

LabelMap Segment(const Volume& volume, const SegmentationParameters& p, const ProgressReporter& progress)
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

  MaskImage::Pointer mask;
  if (!p.seeds.empty())
  {
    auto connected = itk::ConnectedThresholdImageFilter<FloatImage, MaskImage>::New();
    connected->SetInput(source);
    connected->SetLower(static_cast<float>(std::max<double>(lower, -std::numeric_limits<float>::max())));
    connected->SetUpper(static_cast<float>(std::min<double>(upper, std::numeric_limits<float>::max())));
    connected->SetReplaceValue(1);
    connected->SetConnectivity(itk::ConnectedThresholdImageFilter<FloatImage, MaskImage>::FaceConnectivity);
    const ImageGeometry& g = volume.geometry;
    for (const Point3& seed : p.seeds)
    {
      if (!g.ContainsPhysical(seed))
      {
        const Point3 a = g.IndexToPhysical({ { 0, 0, 0 } });
        const Point3 b = g.IndexToPhysical({ { double(g.size[0] - 1), double(g.size[1] - 1), double(g.size[2] - 1) } });
        throw SeedError("seed " + Format(seed) + " mm (LPS) is outside the volume, whose voxel centres run from " +
          Format(a) + " to " + Format(b));
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
        msg << "seed " << Format(seed) << " mm (LPS), voxel (" << index[0] << ", " << index[1]
            << ", " << index[2] << "), is in background: " << quantity << " " << value
            << " is outside [" << lower << ", " << (upper >= 1e30 ? std::string("inf") : std::to_string(upper)) << "]";
        throw SeedError(msg.str());
      }
      connected->AddSeed(index);
    }
    detail::WatchFilter(connected, progress, "connected region");
    connected->Update();
    mask = connected->GetOutput();
    mask->DisconnectPipeline();
  }
  else
  {
    mask = LargestComponent(source, lower, upper, progress);
  }
  progress.ThrowIfCancelled("segmentation");

  // Fill holes, closing and the level set run on the mask's bounding box only.
  std::array<long, 3> pad{ { 2, 2, 2 } };
  std::array<long, 3> closingRadius{ { 0, 0, 0 } };
  for (int c = 0; c < 3; ++c)
  {
    if (p.closingRadius > 0.0)
    {
      closingRadius[c] = std::max(1L, std::lround(p.closingRadius / volume.geometry.spacing[c]));
    }
    pad[c] += closingRadius[c];
    if (p.levelSetIterations > 0)
    {
      pad[c] += 3 + std::lround(2.0 * p.levelSetSigma / volume.geometry.spacing[c]);
    }
  }
  const MaskImage::RegionType box = BoundingRegion(mask, pad);
  if (box.GetNumberOfPixels() == 0)
  {
    throw SegmentationError("segmentation is empty: no voxel in the " + quantity + " window");
  }
  MaskImage::Pointer work = Crop<MaskImage>(mask, box);

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
    FloatImage::Pointer intensity = Crop<FloatImage>(input, box);
    work = RefineWithLevelSet(intensity, work, p, progress);
  }
  if (p.fillHoles)
  {
    auto fill = itk::BinaryFillholeImageFilter<MaskImage>::New();
    fill->SetInput(work);
    fill->SetForegroundValue(1);
    fill->SetFullyConnected(false);
    detail::WatchFilter(fill, progress, "fill holes");
    fill->Update();
    work = fill->GetOutput();
    work->DisconnectPipeline();
  }
  progress.ThrowIfCancelled("segmentation");

  LabelMap result;
  result.geometry = volume.geometry;
  result.voxels.assign(volume.geometry.VoxelCount(), 0);
  const auto boxSize = box.GetSize();
  const auto boxIndex = box.GetIndex();
  const unsigned char* src = work->GetBufferPointer();
  for (std::size_t k = 0; k < boxSize[2]; ++k)
  {
    for (std::size_t j = 0; j < boxSize[1]; ++j)
    {
      const unsigned char* row = src + boxSize[0] * (j + boxSize[1] * k);
      std::copy(row, row + boxSize[0],
        result.voxels.begin() +
          static_cast<std::ptrdiff_t>(result.geometry.LinearIndex(static_cast<std::size_t>(boxIndex[0]),
            j + static_cast<std::size_t>(boxIndex[1]), k + static_cast<std::size_t>(boxIndex[2]))));
    }
  }
  if (result.CountInside() == 0)
  {
    throw SegmentationError("segmentation is empty after refinement");
  }
  return result;
}

} // namespace

void ValidateSegmentationParameters(const SegmentationParameters& p)
{
  Require(std::isfinite(p.lower) && !std::isnan(p.upper) && p.lower <= p.upper,
    "window: need finite lower <= upper");
  for (const Point3& s : p.seeds)
  {
    Require(std::isfinite(s[0]) && std::isfinite(s[1]) && std::isfinite(s[2]), "seeds: non-finite coordinate");
  }
  Require(p.closingRadius >= 0.0 && p.closingRadius <= 5.0, "closingRadius: must be in [0, 5] mm");
  Require(p.minRadius >= 0.1 && p.minRadius <= p.maxRadius && p.maxRadius <= 20.0,
    "vessel radii: need 0.1 <= minRadius <= maxRadius <= 20 mm");
  Require(p.scales >= 1 && p.scales <= 10, "scales: must be in [1, 10]");
  Require(p.alpha > 0.0 && p.alpha <= 2.0 && p.beta > 0.0 && p.beta <= 2.0 && p.gamma > 0.0,
    "alpha/beta/gamma: need alpha, beta in (0, 2] and gamma > 0");
  Require(p.vesselnessThreshold > 0.0 && p.vesselnessThreshold < 1.0,
    "vesselnessThreshold: must be in (0, 1)");
  Require(p.levelSetIterations >= 0 && p.levelSetIterations <= 1000,
    "levelSetIterations: must be in [0, 1000]");
  Require(p.levelSetSigma > 0.0 && p.levelSetSigma <= 5.0, "levelSetSigma: must be in (0, 5] mm");
  Require(p.levelSetPropagation >= -1.0 && p.levelSetPropagation <= 1.0,
    "levelSetPropagation: must be in [-1, 1]");
  Require(p.levelSetCurvature >= 0.0 && p.levelSetCurvature <= 5.0,
    "levelSetCurvature: must be in [0, 5]");
}

LabelMap SegmentVessels(
  const Volume& volume, const SegmentationParameters& parameters, const ProgressReporter& progress)
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

Volume ComputeVesselness(
  const Volume& volume, const SegmentationParameters& parameters, const ProgressReporter& progress)
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
