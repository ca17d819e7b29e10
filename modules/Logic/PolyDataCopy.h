#ifndef bender_PolyDataCopy_h
#define bender_PolyDataCopy_h

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

namespace bender
{

/// A deep copy of surface (points, cells and all data arrays), independent of later changes
/// to it: what the history and the jobs keep of a surface the GUI thread goes on editing.
inline vtkSmartPointer<vtkPolyData> DeepCopyOf(vtkPolyData* surface)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(surface);
  return copy;
}

} // namespace bender

#endif
