#ifndef bender_VesselClipPasses_h
#define bender_VesselClipPasses_h

// The two halves of ClipVesselEnds (VesselClip.h describes the method): the vessel ends of the
// centerlines and where to cut them (CenterlineEnds.cxx), and the cut of the surface by a
// plane within a ball (VesselEndCut.cxx). Internal to bender_vessels.

#include "VesselClip.h"

#include "Vec3.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

class vtkPolyData;

namespace bender
{
namespace clip
{
using V3 = std::array<double, 3>;
using Tri = std::array<std::int64_t, 3>;

// ---- the centerline side (CenterlineEnds.cxx) -------------------------------------------------
/// A centerline walked from a vessel end inwards: positions, arc length, inscribed radius.
struct Profile
{
  std::vector<V3> x;
  std::vector<double> s;
  std::vector<double> r;
  bool atBifurcation = false;    ///< x[0] is a bifurcation (cell data of the branches)
  bool endAtBifurcation = false; ///< x.back() is a bifurcation

  double Length() const { return this->s.empty() ? 0.0 : this->s.back(); }
  /// Position and radius at arc length `along` (clamped).
  V3 At(double along, double* radius = nullptr) const
  {
    along = std::clamp(along, 0.0, this->Length());
    const std::vector<double>& sv = this->s;
    auto it = std::upper_bound(sv.begin(), sv.end(), along);
    std::size_t i = it == sv.begin() ? 0 : static_cast<std::size_t>(it - sv.begin()) - 1;
    if (i + 1 >= sv.size())
    {
      if (radius)
      {
        *radius = this->r.back();
      }
      return this->x.back();
    }
    const double t = sv[i + 1] > sv[i] ? (along - sv[i]) / (sv[i + 1] - sv[i]) : 0.0;
    if (radius)
    {
      *radius = this->r[i] + t * (this->r[i + 1] - this->r[i]);
    }
    return Lerp(this->x[i], this->x[i + 1], t);
  }
  /// Unit tangent pointing inwards (away from the end) at `along`, over a window of one radius.
  V3 Tangent(double along) const
  {
    double radius = 0;
    this->At(along, &radius);
    const double h = std::max(0.5 * radius, 1e-9);
    V3 t = Sub(this->At(along + h), this->At(along - h));
    if (Norm(t) == 0.0)
    {
      t = Sub(this->x.back(), this->x.front());
    }
    return Normalized(t);
  }
};

struct EndGroup
{
  V3 position;
  double radius = 0;
  Profile longest;
  std::vector<Profile> profiles;
};

/// The vessel ends of the centerlines (VesselClip.h): each with its profiles, the longest
/// first. Throws InputError for centerlines without polylines or radius.
std::vector<EndGroup> EndGroups(vtkPolyData* centerlines);

/// The default clip distance of an end (see VesselClip.h).
double SettledDistance(const Profile& p);

// ---- the surface side (VesselEndCut.cxx) ------------------------------------------------------
struct Mesh
{
  std::vector<V3> x;
  std::vector<Tri> t;
};

/// Cuts the mesh by the plane (c, n) within a ball around c of 1.5 `inscribed` radii, widened up
/// to 4 until the ring of crossed triangles closes around the vessel, and removes the side
/// towards n beyond the ring; `rim` gets the new rim's point ids. False (mesh unchanged) when
/// no ring closes.
bool Cut(Mesh& mesh, const V3& c, const V3& n, double inscribed, std::vector<std::int64_t>& rim);

/// Removes unused points and keeps the largest edge-connected component; maps the ends' rim ids.
void Compact(Mesh& mesh, std::vector<ClippedEnd>& ends, std::vector<std::string>& warnings);

} // namespace clip
} // namespace bender

#endif
