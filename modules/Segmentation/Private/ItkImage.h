#ifndef bender_Private_ItkImage_h
#define bender_Private_ItkImage_h

// Internal to bender_segmentation: the only place where Volume/LabelMap meet itk::Image.
// Not included by any public header.

#include "Progress.h"
#include "SegmentationErrors.h"
#include "Volume.h"

#include <itkCommand.h>
#include <itkImage.h>
#include <itkProcessObject.h>

#include <algorithm>
#include <functional>
#include <string>

namespace bender
{
namespace detail
{

using FloatImage = itk::Image<float, 3>;
using MaskImage = itk::Image<unsigned char, 3>;

template<typename TImage>
void SetItkGeometry(TImage* image, const ImageGeometry& g)
{
  typename TImage::RegionType region;
  typename TImage::SpacingType spacing;
  typename TImage::PointType origin;
  typename TImage::DirectionType direction;
  for (unsigned c = 0; c < 3; ++c)
  {
    region.SetSize(c, g.size[c]);
    region.SetIndex(c, 0);
    spacing[c] = g.spacing[c];
    origin[c] = g.origin[c];
    for (unsigned r = 0; r < 3; ++r)
    {
      direction(r, c) = g.direction[3 * r + c];
    }
  }
  image->SetRegions(region);
  image->SetSpacing(spacing);
  image->SetOrigin(origin);
  image->SetDirection(direction);
}

template<typename TImage>
ImageGeometry GetItkGeometry(const TImage* image)
{
  ImageGeometry g;
  const auto region = image->GetLargestPossibleRegion();
  for (unsigned c = 0; c < 3; ++c)
  {
    g.size[c] = region.GetSize(c);
    g.spacing[c] = image->GetSpacing()[c];
    g.origin[c] = image->GetOrigin()[c];
    for (unsigned r = 0; r < 3; ++r)
    {
      g.direction[3 * r + c] = image->GetDirection()(r, c);
    }
  }
  // A buffered region that does not start at 0 moves the first voxel.
  if (region.GetIndex(0) != 0 || region.GetIndex(1) != 0 || region.GetIndex(2) != 0)
  {
    typename TImage::PointType p;
    image->TransformIndexToPhysicalPoint(region.GetIndex(), p);
    g.origin = { { p[0], p[1], p[2] } };
  }
  return g;
}

/// Wraps the caller's buffer without copying; the buffer must outlive the image.
template<typename TPixel>
typename itk::Image<TPixel, 3>::Pointer WrapBuffer(const ImageGeometry& g, const TPixel* data)
{
  using ImageType = itk::Image<TPixel, 3>;
  auto image = ImageType::New();
  SetItkGeometry(image.GetPointer(), g);
  image->GetPixelContainer()->SetImportPointer(const_cast<TPixel*>(data),
    static_cast<typename ImageType::PixelContainer::ElementIdentifier>(g.VoxelCount()),
    false);
  return image;
}

inline FloatImage::Pointer WrapVolume(const Volume& v)
{
  return WrapBuffer<float>(v.geometry, v.voxels.data());
}
inline MaskImage::Pointer WrapLabelMap(const LabelMap& m)
{
  return WrapBuffer<unsigned char>(m.geometry, m.voxels.data());
}

template<typename TImage, typename TPixel>
void CopyBuffer(const TImage* image, std::vector<TPixel>& out)
{
  const auto n = image->GetBufferedRegion().GetNumberOfPixels();
  out.resize(n);
  const auto* src = image->GetBufferPointer();
  std::transform(src, src + n, out.begin(), [](auto v) { return static_cast<TPixel>(v); });
}

/// Forwards an ITK filter's progress to the reporter and aborts it when the cancel flag is set
/// (ITK then throws itk::ProcessAborted, turned into SegmentationCancelled by the caller).
inline void WatchFilter(itk::ProcessObject* filter,
  const ProgressReporter& reporter,
  const std::string& stage)
{
  auto command = itk::CStyleCommand::New();
  auto onProgress = [filter, &reporter, stage]()
  {
    reporter.Report(stage, static_cast<double>(filter->GetProgress()));
    if (reporter.Cancelled())
    {
      filter->AbortGenerateDataOn();
    }
  };
  struct Callback
  {
    std::function<void()> fn;
  };
  auto* callback = new Callback{ onProgress };
  command->SetClientData(callback);
  command->SetCallback(
    [](itk::Object*, const itk::EventObject&, void* data) { static_cast<Callback*>(data)->fn(); });
  command->SetClientDataDeleteCallback([](void* data) { delete static_cast<Callback*>(data); });
  filter->AddObserver(itk::ProgressEvent(), command);
}

} // namespace detail
} // namespace bender

#endif
