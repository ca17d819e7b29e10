#include "ItkVtkBridge.h"

#include "Private/ItkImage.h"

#include <itkVTKImageExport.h>

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageCast.h>
#include <vtkImageData.h>
#include <vtkImageImport.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <cstring>

namespace bender
{
namespace
{

template<typename TImage>
vtkSmartPointer<vtkImageData> ExportToVtk(TImage* image)
{
  auto exporter = itk::VTKImageExport<TImage>::New();
  exporter->SetInput(image);
  vtkNew<vtkImageImport> importer;
  importer->SetUpdateInformationCallback(exporter->GetUpdateInformationCallback());
  importer->SetPipelineModifiedCallback(exporter->GetPipelineModifiedCallback());
  importer->SetWholeExtentCallback(exporter->GetWholeExtentCallback());
  importer->SetSpacingCallback(exporter->GetSpacingCallback());
  importer->SetOriginCallback(exporter->GetOriginCallback());
  importer->SetDirectionCallback(exporter->GetDirectionCallback());
  importer->SetScalarTypeCallback(exporter->GetScalarTypeCallback());
  importer->SetNumberOfComponentsCallback(exporter->GetNumberOfComponentsCallback());
  importer->SetPropagateUpdateExtentCallback(exporter->GetPropagateUpdateExtentCallback());
  importer->SetUpdateDataCallback(exporter->GetUpdateDataCallback());
  importer->SetDataExtentCallback(exporter->GetDataExtentCallback());
  importer->SetBufferPointerCallback(exporter->GetBufferPointerCallback());
  importer->SetCallbackUserData(exporter->GetCallbackUserData());
  importer->Update();
  // The importer's output points into the ITK buffer: copy so that the result stands alone.
  auto output = vtkSmartPointer<vtkImageData>::New();
  output->DeepCopy(importer->GetOutput());
  // The direction came through the exporter's callback; make sure the copy carries it too.
  output->SetDirectionMatrix(importer->GetDataDirection());
  return output;
}

} // namespace

vtkSmartPointer<vtkImageData> VolumeToVtkImage(const Volume& volume)
{
  auto image = detail::WrapVolume(volume);
  return ExportToVtk<detail::FloatImage>(image);
}

vtkSmartPointer<vtkImageData> LabelMapToVtkImage(const LabelMap& mask)
{
  auto image = detail::WrapLabelMap(mask);
  return ExportToVtk<detail::MaskImage>(image);
}

Volume VtkImageToVolume(vtkImageData* image)
{
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  if (!scalars || scalars->GetNumberOfComponents() != 1)
  {
    throw ParameterError("VTK image: no single-component point scalars");
  }
  Volume volume;
  ImageGeometry& g = volume.geometry;
  int extent[6];
  image->GetExtent(extent);
  double origin[3];
  image->GetOrigin(origin);
  double spacing[3];
  image->GetSpacing(spacing);
  vtkMatrix3x3* direction = image->GetDirectionMatrix();
  for (int c = 0; c < 3; ++c)
  {
    g.size[c] = static_cast<std::size_t>(extent[2 * c + 1] - extent[2 * c] + 1);
    g.spacing[c] = spacing[c];
    g.origin[c] = origin[c];
    for (int r = 0; r < 3; ++r)
    {
      g.direction[3 * r + c] = direction->GetElement(r, c);
    }
  }
  // VTK's physical point of index e is origin + D * (spacing .* e): fold the extent start in.
  g.origin = g.IndexToPhysical({ { static_cast<double>(extent[0]),
    static_cast<double>(extent[2]),
    static_cast<double>(extent[4]) } });
  vtkNew<vtkImageCast> cast;
  cast->SetInputData(image);
  cast->SetOutputScalarTypeToFloat();
  cast->Update();
  vtkDataArray* floats = cast->GetOutput()->GetPointData()->GetScalars();
  volume.voxels.resize(g.VoxelCount());
  std::memcpy(
    volume.voxels.data(), floats->GetVoidPointer(0), sizeof(float) * volume.voxels.size());
  return volume;
}

} // namespace bender
