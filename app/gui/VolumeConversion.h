#ifndef VolumeConversion_h
#define VolumeConversion_h

#include "Volume.h"

#include <vtkSmartPointer.h>

class vtkImageData;

/// bender::Volume / LabelMap (LPS mm, direction matrix) as vtkImageData for display, with the
/// origin, spacing and direction kept so that slices overlay the surface exactly.
vtkSmartPointer<vtkImageData> ToImageData(const bender::Volume& volume);
vtkSmartPointer<vtkImageData> ToImageData(const bender::LabelMap& mask);

#endif
