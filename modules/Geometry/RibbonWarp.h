#ifndef bender_RibbonWarp_h
#define bender_RibbonWarp_h

#include "Ribbon.h"
#include "Screw.h"
#include "WarpPlan.h"
#include "WireProjection.h"

#include <string>
#include <vector>

namespace bender
{

/// Samples of s in [0, 1], uniform on each piece between 0, the junction parameters of the two
/// wires and 1 (the relative motion is smooth in s except at the junctions, where the
/// curvature jumps, so linear interpolation between these samples is second order everywhere).
struct SampleGrid
{
  struct Piece
  {
    double start = 0.0;
    double end = 1.0;
    double scale = 0.0; ///< (samples - 1) / length
    int offset = 0;     ///< index of the piece's first sample
    int last = 0;       ///< index of the piece's last sample
  };

  std::vector<Piece> pieces;
  std::vector<double> s;

  /// About `samples` samples in all (at least 2 per piece); knots closer than one spacing to a
  /// neighbour are dropped.
  static SampleGrid Build(double knot1, double knot2, int samples);
  /// The piece holding s (clamped to [0, 1]).
  const Piece& PieceOf(double s) const;
  /// The sample nearest to s.
  int Nearest(double s) const;
};

/// How points with two projections inside the region of influence are warped (spec 6).
enum class BlendMode
{
  TwoProjections,  ///< normative default: both screws at the combined weight, averaged
  SingleProjection ///< nearest projection only; tears space (paper Fig. 8), for comparison
};

struct WarpOptions
{
  BlendMode blend = BlendMode::TwoProjections;
  /// Samples of the screw sign table along s (spec 4.4); doubled automatically until the
  /// rotation changes by less than 90 degrees between samples. At least 1024.
  int signTableSamples = 2048;
};

/// The ribbon warp of one (initial ribbon, final ribbon) pair with its parameters: the
/// continuous lift of the screws along s, validation (convention 11) and exact evaluation of
/// single points. Immutable once built; cheap enough to rebuild on every move of the final
/// ribbon (about 0.2 ms for the sign table).
///
/// Coordinates are those of the mesh the warp is applied to (LPS mm for segmented vessels).
class RibbonWarp
{
public:
  /// Validates and builds. Throws InvalidRibbonError for an unusable ribbon and
  /// InvalidWarpError for parameters out of range (radius, decay.plateau) or a warp that turns
  /// more than 340 degrees relative to its grab; field() is relative to the warp
  /// ("initial.start.tangent", "final", "radius", "decay.plateau", ...). Both are
  /// GeometryError.
  explicit RibbonWarp(const WarpSpec& spec, const WarpOptions& options = {});

  /// Throws exactly as the constructor would; returns normally for a valid warp.
  static void Validate(const WarpSpec& spec);

  const WarpSpec& Spec() const { return this->Input; }
  const WarpOptions& Options() const { return this->Opts; }
  const Ribbon& Initial() const { return this->InitialRibbon; }
  const Ribbon& Final() const { return this->FinalRibbon; }

  /// r_min of the initial and of the final wire (infinite for straight wires).
  double InitialMinimumRadius() const { return this->InitialRibbon.Wire().MinimumRadius(); }
  double FinalMinimumRadius() const { return this->FinalRibbon.Wire().MinimumRadius(); }
  /// R >= r_min of the initial or the final wire: space inversion is possible (paper 3.8).
  bool SpaceInversionRisk() const;
  /// A sentence for the user describing the space-inversion risk, empty when there is none.
  std::string SpaceInversionWarning() const;
  /// True when the continuity lift chose the non-minimal screw somewhere along the wire (the
  /// paper's Fig. 10 case; the UI then offers the reverseScrews toggle).
  bool FlipOccurred() const { return this->AnyFlip; }

  /// The lifted screw carrying C_s to C'_s (spec 4.1, 4.4).
  Screw ScrewAt(double s) const;
  /// The lifted relative motion at s as a unit dual quaternion (the screw above).
  DualQuaternion MotionAt(double s) const;

  /// The decay weight of a projection at distance D.
  double Weight(double distance) const;

  /// Exact warp of one point (projection, weights, screws; spec 6). P' = P outside R.
  Vec3 Apply(const Vec3& p) const;
  /// Same, with the projections given (as found by ProjectOntoWire on the initial wire).
  Vec3 Apply(const Vec3& p, const WireProjections& projections) const;

  /// The lifted relative motions at the samples of Grid(), for fast table evaluation.
  const std::vector<DualQuaternion>& MotionTable() const { return this->Table; }
  /// The samples of s of the sign table (piecewise uniform, split at both junctions).
  const SampleGrid& Grid() const { return this->Samples; }
  /// The lifted rotation quaternions at the samples of Grid() (the sign reference of MotionAt).
  const std::vector<Quaternion>& LiftedRotations() const { return this->Lifted; }

  /// A ribbon's frames C_s in closed form: on each arc, M(s) = Rot(n, theta u) Rot(T_a, tau s +
  /// c) M_a with n the arc's axis, T_a its start tangent and M_a a fixed frame (spec 2.2 with
  /// the twist and the transport composed), so a frame costs two sincos and a few products
  /// instead of the frame matrix and its quaternion.
  struct FramePath
  {
    struct Piece
    {
      Arc arc;
      Quaternion base;        ///< orientation of M_a
      double twistOffset = 0; ///< c: 0 on arc 1, -tau on arc 2
    };
    double sJ = 0.5;
    double tau = 0.0;
    Piece pieces[2];

    explicit FramePath(const Ribbon& ribbon);
    FramePath() = default;
    /// Orientation (a unit quaternion, sign arbitrary but continuous on each arc) and origin of
    /// C_s.
    void At(double s, Quaternion& q, Vec3& origin) const;
  };

  /// The closed-form frames of the initial and of the final ribbon.
  const FramePath& InitialFrames() const { return this->InitialPath; }
  const FramePath& FinalFrames() const { return this->FinalPath; }

private:
  /// The lifted relative motion at s from the closed-form frames, its sign matched to `near`.
  DualQuaternion LiftedMotion(double s, const Quaternion& near) const;

  WarpSpec Input;
  WarpOptions Opts;
  Ribbon InitialRibbon;
  Ribbon FinalRibbon;
  FramePath InitialPath;
  FramePath FinalPath;
  SampleGrid Samples;
  std::vector<Quaternion> Lifted; // lifted rotation quaternions on the sign table
  std::vector<DualQuaternion> Table;
  bool AnyFlip = false;

  bool TryBuildSignTable(int samples);
};

} // namespace bender

#endif
