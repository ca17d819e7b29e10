#ifndef bender_VesselArrayNames_h
#define bender_VesselArrayNames_h

// Array names of Bender's centerlines, in one place. The point-data names are those VMTK,
// 3D Slicer's VMTK extension, morphMan and svMorph read and write, so that centerlines
// written by Bender open in those tools and theirs open here.

namespace bender
{
namespace VesselArrays
{
/// Point data, mm: radius of the largest sphere centred on the point inside the lumen.
constexpr const char* MaximumInscribedSphereRadius = "MaximumInscribedSphereRadius";
/// Point data, mm: arc length from the inlet along the centerline.
constexpr const char* Abscissa = "Abscissa";
/// Point data, unit vectors: Frenet tangent (inlet to outlet) and normal.
constexpr const char* FrenetTangent = "FrenetTangent";
constexpr const char* FrenetNormal = "FrenetNormal";
/// Point data: curvature (1/mm) and torsion (1/mm, signed).
constexpr const char* Curvature = "Curvature";
constexpr const char* Torsion = "Torsion";
/// Cell data of the branch output: the branch's id (= cell index), its parent branch (-1 for
/// the branch leaving the inlet), the bifurcation it starts and ends at (-1 at a vessel end)
/// and the endpoint it ends at (-1 when it ends at a bifurcation).
constexpr const char* BranchId = "BranchId";
constexpr const char* ParentBranchId = "ParentBranchId";
constexpr const char* StartBifurcationId = "StartBifurcationId";
constexpr const char* EndBifurcationId = "EndBifurcationId";
constexpr const char* EndpointId = "EndpointId";
/// Cell data of the per-outlet path output: index of the outlet endpoint of the path.
constexpr const char* CenterlineId = "CenterlineIds";
/// Field data of the branch output: bifurcation points (3 components, mm).
constexpr const char* BifurcationPoints = "BifurcationPoints";
} // namespace VesselArrays
} // namespace bender

#endif
