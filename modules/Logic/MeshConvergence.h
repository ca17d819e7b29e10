#ifndef bender_MeshConvergence_h
#define bender_MeshConvergence_h

// Mesh convergence of one quantity from three meshes (issue 23): Richardson extrapolation with
// the apparent order of convergence and Roache's grid convergence index, following the
// procedure of Celik et al. 2008 ("Procedure for estimation and reporting of uncertainty due to
// discretization in CFD applications", J. Fluids Eng. 130, 078001), which allows unequal
// refinement ratios: the apparent order p solves
//
//   p = | ln|e32 / e21| + ln((r21^p - s) / (r32^p - s)) | / ln r21,   s = sign(e32 / e21),
//
// with h1 < h2 < h3 the cell sizes (1 the finest), r21 = h2 / h1, r32 = h3 / h2,
// e21 = f2 - f1, e32 = f3 - f2. Then
//
//   f_ext = (r21^p f1 - f2) / (r21^p - 1),
//   GCI_fine = Fs |f1 - f2| / |f1| / (r21^p - 1),   Fs = 1.25.
//
// No NaN comes out: oscillatory or diverging sequences, and values that do not change, are
// classified and said in one line instead of extrapolated.

#include <array>
#include <optional>
#include <string>

namespace bender
{

/// One mesh of a study: its characteristic cell size (any length unit, the same for the three)
/// and the value of the quantity on it.
struct MeshSample
{
  double cellSize = 0.0;
  double value = 0.0;
};

/// How the three values behave from the coarsest to the finest mesh.
enum class ConvergenceKind
{
  Monotone,    ///< the changes keep their sign and shrink: extrapolated, with order and GCI
  Oscillatory, ///< the changes alternate in sign: no order, the values' range is the uncertainty
  Diverging,   ///< the changes keep their sign but do not shrink: no order, no extrapolation
  Unchanged    ///< the two finest values agree to round-off: no order is measurable
};

/// The smallest refinement ratio accepted between consecutive meshes (Celik et al. advise
/// more than 1.3 so that the discretization error stands out of other errors).
constexpr double MinimumRefinementRatio = 1.3;
/// Roache's safety factor for a three-mesh study.
constexpr double GciSafetyFactor = 1.25;

/// A three-mesh study of one quantity. Index 0 is the finest mesh, 2 the coarsest.
struct MeshConvergence
{
  ConvergenceKind kind = ConvergenceKind::Unchanged;
  std::array<double, 3> cellSizes{}; ///< h1 < h2 < h3
  std::array<double, 3> values{};    ///< f1, f2, f3
  double ratio21 = 0.0;              ///< h2 / h1
  double ratio32 = 0.0;              ///< h3 / h2
  /// Apparent order p (Monotone only; 0 otherwise).
  double order = 0.0;
  /// Richardson-extrapolated value (Monotone); the finest value otherwise.
  double extrapolated = 0.0;
  /// |f1 - f2| / |f1|: the approximate relative error of the finest mesh (0 when f1 = 0).
  double relativeError = 0.0;
  /// |f_ext - f1| / |f_ext| (Monotone and f_ext != 0; 0 otherwise).
  double extrapolatedRelativeError = 0.0;
  /// Fine-grid GCI as a fraction of |f1| (Monotone and f1 != 0; 0 otherwise).
  double gci = 0.0;
  /// The uncertainty band of the finest value in the quantity's unit: Fs |f1 - f2| / (r21^p - 1)
  /// (Monotone), half the range of the three values (Oscillatory), 0 otherwise.
  double uncertainty = 0.0;
  /// One line: what the sequence does and, unless Monotone, why nothing is extrapolated.
  std::string note;
};

/// The study of three samples in any order. Throws InputError (one line naming the sample) for a
/// non-finite value or cell size, a cell size <= 0, or consecutive sizes whose ratio is below
/// MinimumRefinementRatio.
MeshConvergence EstimateMeshConvergence(const std::array<MeshSample, 3>& samples);

/// How far the coarsest mesh's value (the default mesh of a study) is from the study's best
/// estimate, as a fraction of it: (f3 - best) / |best|, the best estimate being the
/// extrapolated value (Monotone) or the finest value where nothing is extrapolated
/// (Oscillatory, whose uncertainty is the values' half range, Celik et al.; Unchanged). None
/// when Diverging or the best estimate is 0.
std::optional<double> CoarsestDeviation(const MeshConvergence& study);

/// "Monotone", "oscillatory", "diverging", "unchanged".
const char* ConvergenceKindName(ConvergenceKind kind);

} // namespace bender

#endif
