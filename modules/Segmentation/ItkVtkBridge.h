#ifndef bender_ItkVtkBridge_h
#define bender_ItkVtkBridge_h

#include "Volume.h"

#include <vtkSmartPointer.h>

class vtkImageData;

namespace bender
{

/// The one ITK -> VTK image bridge of the project (itk::VTKImageExport + vtkImageImport, the
/// direction callback included). The returned image owns a copy of the voxels; its origin,
/// spacing and direction matrix (VTK >= 9.0) are the volume's, so
/// vtkImageData::TransformIndexToPhysicalPoint gives LPS mm. Note that most VTK 9.1 filters
/// ignore the direction matrix: surface extraction applies it explicitly.
vtkSmartPointer<vtkImageData> VolumeToVtkImage(const Volume& volume);
/// As VolumeToVtkImage, unsigned char scalars (0/1).
vtkSmartPointer<vtkImageData> LabelMapToVtkImage(const LabelMap& mask);

/// VTK -> Volume: single-component point scalars of any type cast to float; origin, spacing,
/// direction matrix and a non-zero extent start kept. Throws ParameterError for an image
/// without single-component scalars.
Volume VtkImageToVolume(vtkImageData* image);

} // namespace bender

#endif
