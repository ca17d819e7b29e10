#include "LabelledSurface.h"

namespace bender
{

LabelledSurface ReadLabelledSurface(vtkPolyData* surface)
{
  LabelledSurface out;
  out.patches = ReadPatchLabels(surface);
  out.surface = surface;
  return out;
}

} // namespace bender
