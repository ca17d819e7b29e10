#ifndef bender_SimdMath_h
#define bender_SimdMath_h

// Branch-free double-precision sin, cos and atan2 for loops that the compiler vectorises
// (ExactWarpKernel, the batched projection of WarpBinding and WireProjection), and the function
// attributes of the instruction sets chosen at run time (SimdLevel.h). Internal to the geometry
// module. The files that use them are compiled without contraction into fused multiply-adds
// (-ffp-contract=off), so a vectorised lane computes bit for bit what the scalar code computes.

#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__GNUC__)
#define BENDER_SIMD_INLINE inline __attribute__((always_inline))
#else
#define BENDER_SIMD_INLINE inline
#endif

#if defined(__GNUC__) && defined(__x86_64__)
/// Defined where the AVX2 and AVX-512 variants of a kernel can be compiled (GCC, Clang on x86-64).
#define BENDER_SIMD_DISPATCH 1
#define BENDER_TARGET_AVX2 __attribute__((target("avx2,fma")))
#define BENDER_TARGET_AVX512 __attribute__((target("avx512f,avx512vl,avx512dq,avx512bw,avx2,fma")))
#endif

namespace bender
{
namespace simd
{

// sin and cos of x (|x| below 2^30), branch-free: x = k pi/2 + r by Cody and Waite's
// three-part pi/2 (fdlibm's constants), Taylor polynomials on |r| <= pi/4 (truncation below
// 1e-17), the quadrant k mod 4 read from the rounding sum's low bits.
BENDER_SIMD_INLINE void SinCos(double x, double& s, double& c)
{
  constexpr double twoOverPi = 0.63661977236758134308;
  constexpr double magic = 6755399441055744.0; // 1.5 * 2^52: adding it rounds to an integer
  const double t = x * twoOverPi + magic;
  const double k = t - magic;
  const double r = ((x - k * 1.57079632673412561417e+00) - k * 6.07710050630396597660e-11) -
    k * 2.02226624871116645580e-21;
  const double r2 = r * r;
  const double sr = r +
    r * r2 *
      (-1.0 / 6.0 +
        r2 *
          (1.0 / 120.0 +
            r2 *
              (-1.0 / 5040.0 +
                r2 *
                  (1.0 / 362880.0 +
                    r2 *
                      (-1.0 / 39916800.0 +
                        r2 *
                          (1.0 / 6227020800.0 +
                            r2 * (-1.0 / 1307674368000.0 + r2 * (1.0 / 355687428096000.0))))))));
  const double cr = 1.0 +
    r2 *
      (-0.5 +
        r2 *
          (1.0 / 24.0 +
            r2 *
              (-1.0 / 720.0 +
                r2 *
                  (1.0 / 40320.0 +
                    r2 *
                      (-1.0 / 3628800.0 +
                        r2 *
                          (1.0 / 479001600.0 +
                            r2 * (-1.0 / 87178291200.0 + r2 * (1.0 / 20922789888000.0))))))));
  std::int64_t bits;
  std::memcpy(&bits, &t, sizeof bits);
  const std::int64_t q = bits & 3;
  const bool swap = (q & 1) != 0;
  const bool negateSin = (q & 2) != 0;
  const bool negateCos = ((q + 1) & 2) != 0;
  const double s0 = swap ? cr : sr;
  const double c0 = swap ? sr : cr;
  s = negateSin ? -s0 : s0;
  c = negateCos ? -c0 : c0;
}

// atan2(y, x) for y >= 0, branch-free: t = min / max in [0, 1], reduced to [-0.2, 0.66] by
// atan(t) = pi/4 + atan((t - 1) / (t + 1)) above 0.66, and Cephes' rational approximation.
BENDER_SIMD_INLINE double Atan2(double y, double x)
{
  constexpr double pio4 = 7.85398163397448278999E-1;
  constexpr double pio2 = 1.57079632679489661923;
  constexpr double pi = 3.14159265358979323846;
  constexpr double moreBits = 6.123233995736765886130E-17; // pi/2 - pio2 rounded
  const double ax = std::fabs(x);
  const bool xBigger = ax > y;
  const double mx = xBigger ? ax : y;
  const double mn = xBigger ? y : ax;
  const bool big = mn > 0.66 * mx;
  const double den = big ? mn + mx : mx;
  const double t = (big ? mn - mx : mn) / (den > 0.0 ? den : 1.0);
  const double z = t * t;
  const double p = (((-8.750608600031904122785E-1 * z - 1.615753718733365076637E1) * z -
                      7.500855792314704667340E1) *
                       z -
                     1.228866684490136173410E2) *
      z -
    6.485021904942025371773E1;
  const double q = ((((z + 2.485846490142306297962E1) * z + 1.650270098316988542046E2) * z +
                      4.328810604912902668951E2) *
                       z +
                     4.853903996359136964868E2) *
      z +
    1.945506571482613964425E2;
  const double at = t + t * z * p / q;
  const double a = big ? pio4 + (at + 0.5 * moreBits) : at;
  const double b = xBigger ? a : (pio2 - a) + moreBits;
  return x < 0.0 ? (pi - b) + 2.0 * moreBits : b;
}

/// atan2(y, x) for any sign of y (Atan2 above on |y|, the sign of y copied as std::atan2 does,
/// including y = -0), within a few units in the last place of std::atan2.
BENDER_SIMD_INLINE double Atan2Signed(double y, double x)
{
  return std::copysign(Atan2(std::fabs(y), x), y);
}

} // namespace simd
} // namespace bender

#endif
