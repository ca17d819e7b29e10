#ifndef bender_LabelledSurface_h
#define bender_LabelledSurface_h

// A surface with its patch table read once (ReadPatchLabels), so that the steps after the
// clip (export, the OpenFOAM case) take the table along instead of parsing the cell data again.

#include "PatchLabels.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <vector>

namespace bender
{

struct LabelledSurface
{
  vtkSmartPointer<vtkPolyData> surface;
  std::vector<PatchLabel> patches; ///< ReadPatchLabels of `surface`: sorted by id
};

/// The surface and ReadPatchLabels of it. Throws ReadPatchLabels' InputError (naming the array)
/// for labels it refuses.
LabelledSurface ReadLabelledSurface(vtkPolyData* surface);

} // namespace bender

#endif
