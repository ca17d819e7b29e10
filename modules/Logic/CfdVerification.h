#ifndef bender_CfdVerification_h
#define bender_CfdVerification_h

// Verification cases built in (issue 23, bender-cli cfd-verify): generated tubes meshed and
// solved by the ordinary OpenFOAM case (WriteOpenFoamCase, RunOpenFoamCase, MapCfdResults), each
// figure measured against a published laminar result with a stated tolerance:
//
//  - a straight tube (D 4 mm, 40 D long, Re 100, uniform inlet): the pressure drop against
//    Shah's developing-flow correlation (3 %), and the wall shear stress of the developed part
//    (8 D to 38 D) against Poiseuille's 8 mu U / D (5 %);
//  - a curved tube (a torus section: D 4 mm, bend radius 2.5 D, 300 degrees, Re 200, Dean 89):
//    the friction ratio f_curved / f_straight of its developed part (180 to 270 degrees), from
//    the wall pressure's gradient along the centreline, against White's correlation (10 %).
//
// The reference formulas are in CfdReferenceFlows.h, the geometry in CfdVerificationTubes.h.

#include "Progress.h"

#include <functional>
#include <string>
#include <vector>

namespace bender
{

/// The wall cells across the diameter each case is meshed with by default: the coarsest that
/// keeps its figures within their tolerances with a margin (docs/cfd.md, verification).
constexpr double StraightCellsAcross = 12.0;
constexpr double CurvedCellsAcross = 16.0;

/// One measured figure against its reference.
struct CfdVerificationFigure
{
  std::string name;   ///< "pressure drop"
  std::string unit;   ///< "Pa", "" for a ratio
  double value = 0.0; ///< measured
  double reference = 0.0;
  std::string source;     ///< "Shah 1978"
  double tolerance = 0.0; ///< allowed |value / reference - 1|, a fraction

  /// value / reference - 1.
  double Deviation() const;
  bool Passed() const;
};

/// One generated case and its figures.
struct CfdVerificationCase
{
  std::string name;        ///< "straight tube", "curved tube"
  std::string folder;      ///< the OpenFOAM case (removed afterwards without a folder option)
  std::string description; ///< geometry and flow in one line: "D 4 mm, L 80 mm, Re 100"
  double cellSize = 0.0;   ///< at the wall, m
  long long cells = 0;     ///< of the OpenFOAM mesh (0 when not known)
  int iterations = 0;
  bool converged = false;    ///< simpleFoam met its residual control
  double pressureDrop = 0.0; ///< from the inlet to the outlet, Pa
  std::vector<CfdVerificationFigure> figures;
};

struct CfdVerificationResult
{
  std::vector<CfdVerificationCase> cases;
  bool Passed() const; ///< every figure of every case within its tolerance
};

/// Which cases, where, and how to report.
struct CfdVerificationOptions
{
  /// Where the cases go (DIR/straight-tube, DIR/curved-tube, each with its surface .vtp); must
  /// be new or empty. Empty: a temporary folder, removed at the end.
  std::string folder;
  bool straight = true;
  bool curved = true;
  /// Wall cells across the tubes' diameter (the case's cell size is D / this), 4 to 200; 0: each
  /// case's own (StraightCellsAcross, CurvedCellsAcross).
  double cellsAcross = 0.0;
  /// simpleFoam's iteration limit (the residual control stops it earlier).
  int iterations = 1500;
  int processors = 1;
  /// Allrun's progress lines, prefixed by the case's name.
  std::function<void(const std::string&)> onLine;
  /// Cancel flag (stops OpenFOAM: Cancelled is thrown); its callback gets the cases' stages.
  ProgressReporter progress;
};

/// Writes, runs and measures the cases. Throws EnvironmentError when OpenFOAM is missing,
/// InputError for bad options or a folder that is not new or empty, Error when a run fails,
/// Cancelled. A figure outside its tolerance is not an error: see Passed().
CfdVerificationResult RunCfdVerification(const CfdVerificationOptions& options);

/// Each case, then each figure against its reference and tolerance, "pass" or "FAIL".
std::string FormatCfdVerification(const CfdVerificationResult& result);

/// One JSON object: format "bender-cfd-verification", cases with their figures, passed.
std::string CfdVerificationToJson(const CfdVerificationResult& result);

} // namespace bender

#endif
