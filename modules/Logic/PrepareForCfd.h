#ifndef bender_PrepareForCfd_h
#define bender_PrepareForCfd_h

// "Prepare for CFD" (issue 11): a vessel surface made ready for a CFD mesher in one call:
//  1. the ends clipped perpendicular to the centerline (VesselClip.h; the centerlines are
//     computed when not given), or, with clip off, the open ends already there;
//  2. names and roles: the largest end is the inlet, the others outlets (outlet_1, outlet_2,
//     ... by decreasing area); names by position (the end whose centre is nearest gets it; an
//     entry marked inlet, or named "inlet", makes its end the inlet);
//  3. flow extensions along each end's outward normal (FlowExtensions.h; default 10 radii at
//     the inlet, 5 at the outlets, per end by position; 0 for none);
//  4. flat quality caps labelled through PatchLabels.h (vtkBenderCapFilter): CellEntityIds and
//     ModelFaceID 1 on the wall (extensions included), 2.. on the caps, PatchNames/PatchTypes.
//     With cap off, the surface stays open and is labelled all wall.
// Units are the surface's (mm for Bender's surfaces); nothing is written to disk.

#include "LabelledSurface.h"
#include "PatchLabels.h"
#include "Progress.h"
#include "VesselClip.h"
#include "WarpPlan.h"

#include <vtkSmartPointer.h>

#include <array>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{

struct CfdEndName
{
  std::array<double, 3> position{ { 0, 0, 0 } };
  std::string name;   ///< a valid patch name (IsValidPatchName), not "wall"
  bool inlet = false; ///< this end is the inlet (also when name is "inlet")
};

struct CfdEndFactor
{
  std::array<double, 3> position{ { 0, 0, 0 } };
  double factor = 0.0; ///< flow-extension length / radius of the nearest end, [0, 100]
};

struct PrepareForCfdOptions
{
  /// Centerlines of the surface (polylines with MaximumInscribedSphereRadius); null: computed.
  vtkSmartPointer<vtkPolyData> centerlines;
  /// Clip the vessel ends (default). Off: use the surface's open ends as they are.
  bool clip = true;
  /// Per-end clip positions or distances (see ClipEndRequest).
  std::vector<ClipEndRequest> ends;
  std::vector<CfdEndName> names;
  double inletExtension = 10.0;               ///< flow-extension factor of the inlet, [0, 100]
  double outletExtension = 5.0;               ///< of the outlets, [0, 100]
  std::vector<CfdEndFactor> extensionFactors; ///< per end, by position
  bool cap = true;
  /// Names the surface in error messages ("aneurysm.stl").
  std::string inputName = "the surface";
};

struct CfdEnd
{
  std::string name;
  int id = 0; ///< CellEntityIds value of its cap (2..); the same numbering when not capped
  PatchType type = PatchType::Outlet;
  std::array<double, 3> centre{ { 0, 0, 0 } }; ///< of the cap (the far end of its extension)
  std::array<double, 3> normal{ { 0, 0, 1 } }; ///< unit, outwards
  double radius = 0.0;                         ///< equivalent radius sqrt(area / pi)
  double area = 0.0;
  double extensionLength = 0.0;
  /// The flow-extension factor it was made with (the options' for this end, else its role's).
  double extensionFactor = 0.0;
  std::array<double, 3> clipCentre{ { 0, 0, 0 } }; ///< centre of the vessel's own rim
  /// With clip: the vessel end on the centerline (CenterlineEndPath::position) and the arc
  /// length from it to the cut (ClipEndRequest{centerlineEnd, clipDistance} cuts there again).
  /// Without clip: clipDistance is -1.
  std::array<double, 3> centerlineEnd{ { 0, 0, 0 } };
  double clipDistance = -1.0;
};

/// The prepared surface is a LabelledSurface: `surface` labelled (PatchLabels.h) and `patches`
/// its table as written (the wall, then each capped end by id; ReadPatchLabels of `surface`
/// gives the same), so that the result goes to the export and the case as it is, without
/// parsing the cell data again.
struct PrepareForCfdResult : LabelledSurface
{
  std::vector<CfdEnd> ends; ///< by id
  std::vector<std::string> warnings;
  /// With clip: the centerlines the ends were clipped by (given, or computed); null without.
  vtkSmartPointer<vtkPolyData> centerlines;
};

/// Throws bender::InputError, one line starting with options.inputName: an empty surface, no
/// centerline, a clip plane that cuts no vessel, fewer than two ends, cap without clip on a
/// surface with no open end, bad names or factors. `progress`: the stages ("centerlines",
/// "clip", "flow extensions", "caps") are reported and the cancel flag is polled between them
/// (bender::Cancelled; nothing returned, `surface` untouched either way).
PrepareForCfdResult PrepareForCfd(vtkPolyData* surface,
  const PrepareForCfdOptions& options = {},
  const ProgressReporter& progress = {});

/// The options of a plan's Prepare for CFD step (WarpPlan.h; no centerlines: computed).
PrepareForCfdOptions CfdStepOptions(const CfdStep& step);
/// The plan step of `options` (clip, cap, the ends' cuts, names and extension factors; not the
/// centerlines nor the input's name), applied after `afterWarps` warps.
CfdStep CfdStepOf(const PrepareForCfdOptions& options, std::size_t afterWarps);
/// `given` with what its result made written out: every end's cut (its centerline end and
/// distance; with clip), name and role (at its rim's centre) and extension factor. Applied to
/// the same surface it makes the same surface, and says so in the plan.
CfdStep ResolvedCfdStep(const CfdStep& given, const PrepareForCfdResult& result);

} // namespace bender

#endif
