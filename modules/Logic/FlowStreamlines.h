#ifndef bender_FlowStreamlines_h
#define bender_FlowStreamlines_h

// Streamlines of a solved case (issue 23, the Flow panel's optional streamlines): the velocity
// of CASE/results/volume.vtu traced downstream from seeds spread over the inlet's cap.

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <string>

namespace bender
{

/// Traces the case's velocity (volume.vtu: point data "U" in m/s, points in mm, LPS) from up to
/// `seeds` points spread over the inlet cap of `surface` (results/surface.vtp: CellEntityIds and
/// the patch table; the cap of the patch of type inlet), each set a little inside the vessel.
/// Returns polylines in mm with point data "Speed" (m/s); empty when no seed lies in the mesh.
/// Throws InputError naming the file: no volume.vtu, no "U" in it, no inlet in `surface`.
vtkSmartPointer<vtkPolyData> FlowStreamlines(const std::string& caseDirectory,
  vtkPolyData* surface,
  int seeds = 60);

} // namespace bender

#endif
