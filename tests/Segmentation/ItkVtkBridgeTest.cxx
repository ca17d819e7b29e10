// The ITK -> VTK bridge keeps the direction matrix: oblique round trip.
#include "SegmentationTestUtilities.h"

#include "ItkVtkBridge.h"
#include "SegmentationErrors.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkPointData.h>

namespace
{

bender::Volume Oblique()
{
  bender::Volume v;
  v.geometry.size = { { 5, 4, 3 } };
  v.geometry.spacing = { { 0.3, 0.6, 1.1 } };
  v.geometry.origin = { { 10.0, -20.0, 35.5 } };
  v.geometry.direction = bender_test::ObliqueDirection();
  for (std::size_t n = 0; n < v.geometry.VoxelCount(); ++n)
  {
    v.voxels.push_back(float(n) * 0.25f);
  }
  return v;
}

TEST(ItkVtkBridge, ObliqueDirectionSurvivesTheRoundTrip)
{
  const bender::Volume volume = Oblique();
  vtkSmartPointer<vtkImageData> image = bender::VolumeToVtkImage(volume);
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(dims[0], 5);
  EXPECT_EQ(dims[1], 4);
  EXPECT_EQ(dims[2], 3);
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(
        image->GetDirectionMatrix()->GetElement(r, c), volume.geometry.direction[3 * r + c], 1e-12);
    }
  }
  // VTK's own index -> physical mapping agrees with the volume's LPS mapping.
  for (const bender::Point3 index :
    { bender::Point3{ { 0, 0, 0 } }, bender::Point3{ { 4, 3, 2 } }, bender::Point3{ { 1, 2, 1 } } })
  {
    double p[3];
    image->TransformContinuousIndexToPhysicalPoint(index[0], index[1], index[2], p);
    const bender::Point3 expected = volume.geometry.IndexToPhysical(index);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(p[c], expected[c], 1e-9);
    }
  }
  EXPECT_FLOAT_EQ(float(image->GetPointData()->GetScalars()->GetTuple1(17)), volume.voxels[17]);

  const bender::Volume back = bender::VtkImageToVolume(image);
  EXPECT_EQ(back.geometry.size, volume.geometry.size);
  for (int e = 0; e < 9; ++e)
  {
    EXPECT_NEAR(back.geometry.direction[e], volume.geometry.direction[e], 1e-12);
  }
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(back.geometry.origin[c], volume.geometry.origin[c], 1e-12);
    EXPECT_NEAR(back.geometry.spacing[c], volume.geometry.spacing[c], 1e-12);
  }
  EXPECT_EQ(back.voxels, volume.voxels);
}

TEST(ItkVtkBridge, ExtentStartIsFoldedIntoTheOrigin)
{
  bender::Volume volume = Oblique();
  vtkSmartPointer<vtkImageData> image = bender::VolumeToVtkImage(volume);
  image->SetExtent(2, 6, 1, 4, 3, 5);
  const bender::Volume moved = bender::VtkImageToVolume(image);
  const bender::Point3 expected = volume.geometry.IndexToPhysical({ { 2, 1, 3 } });
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(moved.geometry.origin[c], expected[c], 1e-9);
  }
}

TEST(ItkVtkBridge, LabelMapsBecomeUnsignedCharAndEmptyImagesAreRejected)
{
  bender::LabelMap mask;
  mask.geometry = Oblique().geometry;
  mask.voxels.assign(mask.geometry.VoxelCount(), 0);
  mask.voxels[7] = 1;
  vtkSmartPointer<vtkImageData> image = bender::LabelMapToVtkImage(mask);
  EXPECT_EQ(image->GetScalarType(), VTK_UNSIGNED_CHAR);
  EXPECT_EQ(image->GetPointData()->GetScalars()->GetTuple1(7), 1.0);
  vtkNew<vtkImageData> empty;
  EXPECT_THROW(bender::VtkImageToVolume(empty), bender::ParameterError);
}

} // namespace
