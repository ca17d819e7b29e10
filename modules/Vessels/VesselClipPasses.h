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
  std::vector<V3> X;
  std::vector<double> S;
  std::vector<double> R;
  bool AtBifurcation = false;    ///< X[0] is a bifurcation (cell data of the branches)
  bool EndAtBifurcation = false; ///< X.back() is a bifurcation

  double Length() const { return S.empty() ? 0.0 : S.back(); }
  /// Position and radius at arc length s (clamped).
  V3 At(double s, double* radius = nullptr) const
  {
    s = std::clamp(s, 0.0, this->Length());
    auto it = std::upper_bound(S.begin(), S.end(), s);
    std::size_t i = it == S.begin() ? 0 : static_cast<std::size_t>(it - S.begin()) - 1;
    if (i + 1 >= S.size())
    {
      if (radius)
      {
        *radius = R.back();
      }
      return X.back();
    }
    const double t = S[i + 1] > S[i] ? (s - S[i]) / (S[i + 1] - S[i]) : 0.0;
    if (radius)
    {
      *radius = R[i] + t * (R[i + 1] - R[i]);
    }
    return Lerp(X[i], X[i + 1], t);
  }
  /// Unit tangent pointing inwards (away from the end) at s, over a window of one radius.
  V3 Tangent(double s) const
  {
    double r = 0;
    this->At(s, &r);
    const double h = std::max(0.5 * r, 1e-9);
    V3 t = Sub(this->At(s + h), this->At(s - h));
    if (Norm(t) == 0.0)
    {
      t = Sub(X.back(), X.front());
    }
    return Normalized(t);
  }
};

struct EndGroup
{
  V3 Position;
  double Radius = 0;
  Profile Longest;
  std::vector<Profile> Profiles;
};

/// The vessel ends of the centerlines (VesselClip.h): each with its profiles, the longest
/// first. Throws InputError for centerlines without polylines or radius.
std::vector<EndGroup> EndGroups(vtkPolyData* centerlines);

/// The default clip distance of an end (see VesselClip.h).
double SettledDistance(const Profile& p);

// ---- the surface side (VesselEndCut.cxx) ------------------------------------------------------
struct Mesh
{
  std::vector<V3> X;
  std::vector<Tri> T;
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
