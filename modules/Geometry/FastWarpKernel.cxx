#include "FastWarpKernel.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace bender
{

void FastWarpKernel::SetMotion(const MotionTable& table, const Vec3& origin)
{
  const std::vector<DualQuaternion>& src = table.Samples();
  const std::size_t n = src.size();
  // Per sample j, 16 contiguous floats: the screw logarithm L_j of the motion (a, b: the
  // motion is exp((0, a) + eps (0, b)), 6 floats, 2 unused), then L_{j+1} - L_j (zero for the
  // last sample), so that inside interval j the logarithm is L_j + alpha (L_{j+1} - L_j): one
  // multiply-add per component, and the power f of the interpolated screw is exp(f L).
  this->Table.assign(16 * n, 0.0f);
  for (std::size_t j = 0; j < n; ++j)
  {
    // Conjugate by the translation to the origin: X_l -> R X_l + (R c + t - c).
    const DualQuaternion& m = src[j];
    const Vec3 t = (m.dual * Conjugate(m.real)).Vector() * 2.0;
    const Vec3 tl = RotateByQuaternion(m.real, origin) + t - origin;
    const Quaternion d = Quaternion{ 0.0, 0.5 * tl.x, 0.5 * tl.y, 0.5 * tl.z } * m.real;
    // The logarithm of the unit dual quaternion (q, d) with q = (cos h, sin h K), the lifted
    // half angle h in [0, pi) (below 170 degrees by the 340 degree rule):
    //   a = h K = v / S,  a.b = -d.w / S,  b = (d.vec - R (a.b) a) / S,
    // with S = sin(h) / h and R = (cos h - S) / h^2 (their series near h = 0).
    const double sv = Norm(m.real.Vector());
    const double h = std::atan2(sv, m.real.w);
    const double h2 = h * h;
    const double S = h > 1e-4 ? sv / h : 1.0 - h2 / 6.0;
    const double R = h > 1e-2 ? (m.real.w - S) / h2 : -1.0 / 3.0 + h2 / 30.0 - h2 * h2 / 840.0;
    const Vec3 a = m.real.Vector() / S;
    const double ab = -d.w / S;
    const Vec3 b = (d.Vector() - a * (R * ab)) / S;
    float* o = this->Table.data() + 16 * j;
    o[0] = static_cast<float>(a.x);
    o[1] = static_cast<float>(a.y);
    o[2] = static_cast<float>(a.z);
    o[3] = static_cast<float>(b.x);
    o[4] = static_cast<float>(b.y);
    o[5] = static_cast<float>(b.z);
  }
  for (std::size_t j = 0; j + 1 < n; ++j)
  {
    float* o = this->Table.data() + 16 * j;
    for (int c = 0; c < 6; ++c)
    {
      o[8 + c] = o[16 + c] - o[c];
    }
  }
  const auto& pieces = table.Pieces();
  for (std::size_t k = 0; k < 3; ++k)
  {
    if (k < pieces.size())
    {
      this->Start[k] = static_cast<float>(pieces[k].start);
      this->End[k] = k + 1 < pieces.size() ? static_cast<float>(pieces[k].end) : 2.0f;
      this->Scale[k] = static_cast<float>(pieces[k].scale);
      this->Offset[k] = pieces[k].offset;
      this->Last[k] = pieces[k].last;
    }
    else
    {
      this->Start[k] = 2.0f;
      this->End[k] = 2.0f;
      this->Scale[k] = 0.0f;
      this->Offset[k] = this->Last[k] = 0;
    }
  }
}

#if defined(__GNUC__)
#define BENDER_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define BENDER_ALWAYS_INLINE inline
#endif

namespace
{
// Taylor polynomials (Horner) of the even functions of the screw exponential, accurate to a
// few float ulps on the range used: y = (theta / 2)^2 <= 2.2 and x = theta^2 <= 8.8.
BENDER_ALWAYS_INLINE float CosOfRoot(float y) // cos(sqrt(y))
{
  return 1.0f +
    y *
    (-1.0f / 2.0f +
      y *
        (1.0f / 24.0f +
          y *
            (-1.0f / 720.0f +
              y *
                (1.0f / 40320.0f +
                  y *
                    (-1.0f / 3628800.0f +
                      y * (1.0f / 479001600.0f - y * (1.0f / 87178291200.0f)))))));
}

BENDER_ALWAYS_INLINE float SincOfRoot(float y) // sin(sqrt(y)) / sqrt(y)
{
  return 1.0f +
    y *
    (-1.0f / 6.0f +
      y *
        (1.0f / 120.0f +
          y *
            (-1.0f / 5040.0f +
              y *
                (1.0f / 362880.0f +
                  y *
                    (-1.0f / 39916800.0f +
                      y * (1.0f / 6227020800.0f - y * (1.0f / 1307674368000.0f)))))));
}

// (cos(theta) - sin(theta) / theta) / theta^2 at x = theta^2: sum over k >= 1 of
// (-1)^k 2k / (2k + 1)! x^(k - 1).
BENDER_ALWAYS_INLINE float CosMinusSincOverSquare(float x)
{
  constexpr double c[10] = { -2.0 / 6.0,
    4.0 / 120.0,
    -6.0 / 5040.0,
    8.0 / 362880.0,
    -10.0 / 39916800.0,
    12.0 / 6227020800.0,
    -14.0 / 1307674368000.0,
    16.0 / 355687428096000.0,
    -18.0 / 121645100408832000.0,
    20.0 / 51090942171709440000.0 };
  float r = static_cast<float>(c[9]);
  for (int k = 8; k >= 0; --k)
  {
    r = static_cast<float>(c[k]) + x * r;
  }
  return r;
}

// The pieces of the table as plain scalars so that the loop below stays branch-free.
struct KernelPieces
{
  float end0, end1;             // piece boundaries (2 where unused)
  float start0, start1, start2; // piece starts in s
  float scale0, scale1, scale2; // samples per unit s
  int first0, first1, first2;   // index of each piece's first sample
  int span0, span1, span2;      // index of its last interval (samples - 2)
};

// One pass over n points: the interval of s (piece chosen by selects, no branch), the motion
// m0 + a (m1 - m0) from the interval's 16 contiguous floats, then the power f and the rigid
// motion applied to P. Every point goes through the same operations whatever its position in
// the range, so a point's result does not depend on how a range is split between threads.
BENDER_ALWAYS_INLINE int KernelBody(const float* table,
  const KernelPieces& pc,
  const float* pxAll,
  const float* pyAll,
  const float* pzAll,
  const float* sp,
  const float* fpAll,
  float* outAll,
  const float* shift,
  int n)
{
  const float sx = shift[0], sy = shift[1], sz = shift[2];
  int nonFinite = 0;
  // Local copies: selects between values in registers if-convert, loads through `pc` do not.
  const float end0 = pc.end0, end1 = pc.end1;
  const float start0 = pc.start0, start1 = pc.start1, start2 = pc.start2;
  const float scale0 = pc.scale0, scale1 = pc.scale1, scale2 = pc.scale2;
  const int first0 = pc.first0, first1 = pc.first1, first2 = pc.first2;
  const int span0 = pc.span0, span1 = pc.span1, span2 = pc.span2;
  constexpr int block = 128;
  alignas(64) int index[block];
  alignas(64) float frac[block];
  alignas(64) float motion[8 * block];
  for (int b = 0; b < n; b += block)
  {
    const int m = n - b < block ? n - b : block;
    // The interval of each s and the fraction in it (vectorised selects, no branch).
    const float* sb = sp + b;
#pragma omp simd
    for (int k = 0; k < m; ++k)
    {
      const float sk = sb[k];
      const bool p1 = sk >= end0;
      const bool p2 = sk >= end1;
      float start = p1 ? start1 : start0;
      float scale = p1 ? scale1 : scale0;
      int first = p1 ? first1 : first0;
      int span = p1 ? span1 : span0;
      start = p2 ? start2 : start;
      scale = p2 ? scale2 : scale;
      first = p2 ? first2 : first;
      span = p2 ? span2 : span;
      // s >= start: the pieces' starts are their predecessors' ends (the same floats) and
      // s >= 0, so u >= 0 and truncation is the floor.
      const float u = (sk - start) * scale;
      // Clamped in float before the conversion (converting a NaN or an out-of-range float to
      // int is undefined behaviour): an s outside [0, 1] or NaN never reads outside the table
      // (NaN compares false, so it becomes interval 0; its result stays NaN and is caught by the
      // finiteness check).
      const float u0 = u > 0.0f ? u : 0.0f;
      const float limit = static_cast<float>(span);
      const int j = static_cast<int>(u0 < limit ? u0 : limit);
      frac[k] = u - static_cast<float>(j);
      index[k] = 16 * (first + j);
    }
    // The screw logarithms L0 + alpha (L1 - L0), eight contiguous floats per point.
    for (int k = 0; k < m; ++k)
    {
      const float* e = table + index[k];
      const float a = frac[k];
      float* o = motion + 8 * k;
      for (int c = 0; c < 8; ++c)
      {
        o[c] = e[c] + a * e[8 + c];
      }
    }
    const float* px = pxAll + b;
    const float* py = pyAll + b;
    const float* pz = pzAll + b;
    const float* fp = fpAll + b;
    float* out = outAll + 3 * b;
#pragma omp simd
    for (int k = 0; k < m; ++k)
    {
      // exp(f L) with L = (0, a) + eps (0, b) the interpolated screw logarithm, theta = |f a|:
      //   real = (cos theta, S f a), dual = (-S (fa.fb), S f b + R (fa.fb) f a),
      // S = sin(theta) / theta, R = (cos(theta) - S) / theta^2; all polynomials in theta^2,
      // through the half angle for cos and S: no division, no square root, no atan2.
      const float* e = motion + 8 * k;
      const float f = fp[k];
      const float ax = f * e[0], ay = f * e[1], az = f * e[2];
      const float bx = f * e[3], by = f * e[4], bz = f * e[5];
      const float x2 = ax * ax + ay * ay + az * az;
      const float ab = ax * bx + ay * by + az * bz;
      const float q2 = 0.25f * x2; // (theta / 2)^2
      const float sh = SincOfRoot(q2);
      const float rw = 1.0f - 2.0f * q2 * sh * sh;
      const float S = sh * CosOfRoot(q2);
      const float R = CosMinusSincOverSquare(x2);
      const float rx = S * ax, ry = S * ay, rz = S * az;
      const float Dw = -S * ab;
      const float Rab = R * ab;
      const float Dx = S * bx + Rab * ax, Dy = S * by + Rab * ay, Dz = S * bz + Rab * az;
      // t = 2 (D conj(r)).vec = 2 (-Dw rv + rw D - D x rv)
      const float tx = 2.0f * (-Dw * rx + rw * Dx - (Dy * rz - Dz * ry));
      const float ty = 2.0f * (-Dw * ry + rw * Dy - (Dz * rx - Dx * rz));
      const float tz = 2.0f * (-Dw * rz + rw * Dz - (Dx * ry - Dy * rx));
      // Rotate P by r: P + rw c + rv x c with c = 2 rv x P.
      const float x = px[k], y = py[k], z = pz[k];
      const float cx = 2.0f * (ry * z - rz * y);
      const float cy = 2.0f * (rz * x - rx * z);
      const float cz = 2.0f * (rx * y - ry * x);
      const float qx = x + rw * cx + (ry * cz - rz * cy) + tx + sx;
      const float qy = y + rw * cy + (rz * cx - rx * cz) + ty + sy;
      const float qz = z + rw * cz + (rx * cy - ry * cx) + tz + sz;
      out[3 * k] = qx;
      out[3 * k + 1] = qy;
      out[3 * k + 2] = qz;
      // q - q is 0 for every finite q and NaN for an infinity or a NaN.
      nonFinite += (qx - qx) + (qy - qy) + (qz - qz) == 0.0f ? 0 : 1;
    }
  }
  return nonFinite;
}

#define BENDER_KERNEL_PARAMETERS                                                                   \
  const float *table, const KernelPieces &pc, const float *px, const float *py, const float *pz,   \
    const float *sp, const float *fp, float *out, const float *shift, int n
#define BENDER_KERNEL_ARGUMENTS table, pc, px, py, pz, sp, fp, out, shift, n

// The same body compiled for the baseline of the build and, on x86-64 with GCC or Clang, for
// AVX2 + FMA and AVX-512; FastWarpKernel picks the best one the CPU has at run time (the
// default build stays portable: no -march flag).
int KernelBaseline(BENDER_KERNEL_PARAMETERS)
{
  return KernelBody(BENDER_KERNEL_ARGUMENTS);
}

using KernelFunction = decltype(&KernelBaseline);

#if defined(__GNUC__) && defined(__x86_64__)
#define BENDER_KERNEL_DISPATCH 1
__attribute__((target("avx2,fma"))) int KernelAvx2(BENDER_KERNEL_PARAMETERS)
{
  return KernelBody(BENDER_KERNEL_ARGUMENTS);
}

__attribute__((target("avx512f,avx512vl,avx512dq,avx512bw,avx2,fma"))) int KernelAvx512(
  BENDER_KERNEL_PARAMETERS)
{
  return KernelBody(BENDER_KERNEL_ARGUMENTS);
}
#endif

KernelFunction KernelOf(FastWarpKernel::SimdLevel level)
{
#ifdef BENDER_KERNEL_DISPATCH
  switch (level)
  {
    case FastWarpKernel::SimdLevel::Avx512:
      return KernelAvx512;
    case FastWarpKernel::SimdLevel::Avx2:
      return KernelAvx2;
    case FastWarpKernel::SimdLevel::Baseline:
      break;
  }
#else
  (void)level;
#endif
  return KernelBaseline;
}

KernelPieces PiecesOf(const float* start,
  const float* end,
  const float* scale,
  const int* offset,
  const int* last)
{
  KernelPieces pc;
  pc.end0 = end[0];
  pc.end1 = end[1];
  pc.start0 = start[0];
  pc.start1 = start[1];
  pc.start2 = start[2];
  pc.scale0 = scale[0];
  pc.scale1 = scale[1];
  pc.scale2 = scale[2];
  pc.first0 = offset[0];
  pc.first1 = offset[1];
  pc.first2 = offset[2];
  pc.span0 = last[0] - offset[0] - 1;
  pc.span1 = last[1] - offset[1] - 1;
  pc.span2 = last[2] - offset[2] - 1;
  return pc;
}
} // namespace

bool FastWarpKernel::Supports(SimdLevel level)
{
#ifdef BENDER_KERNEL_DISPATCH
  // May run during static initialisation (ExactWarpKernel picks its kernel then), before the
  // CPU model is read: read it here.
  __builtin_cpu_init();
#endif
  switch (level)
  {
    case SimdLevel::Baseline:
      return true;
#ifdef BENDER_KERNEL_DISPATCH
    case SimdLevel::Avx2:
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    case SimdLevel::Avx512:
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
        __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
        __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#endif
    default:
      return false;
  }
}

FastWarpKernel::SimdLevel FastWarpKernel::BestLevel()
{
  static const SimdLevel best = Supports(SimdLevel::Avx512)
    ? SimdLevel::Avx512
    : (Supports(SimdLevel::Avx2) ? SimdLevel::Avx2 : SimdLevel::Baseline);
  return best;
}

const char* FastWarpKernel::LevelName(SimdLevel level)
{
  switch (level)
  {
    case SimdLevel::Avx512:
      return "AVX-512";
    case SimdLevel::Avx2:
      return "AVX2+FMA";
    default:
      return "baseline";
  }
}

bool FastWarpKernel::SetLevel(SimdLevel level)
{
  if (!Supports(level))
  {
    return false;
  }
  this->Simd = level;
  return true;
}

void FastWarpKernel::Evaluate(const FastWarpPoints& points,
  const std::array<float*, 3>& out,
  std::size_t begin,
  std::size_t end) const
{
  constexpr std::size_t block = 512;
  alignas(64) float xyz[3 * block];
  for (std::size_t b = begin; b < end; b += block)
  {
    const std::size_t n = std::min(block, end - b);
    this->EvaluateInterleaved(points.From(b), xyz, nullptr, 0, n);
    for (std::size_t k = 0; k < n; ++k)
    {
      out[0][b + k] = xyz[3 * k];
      out[1][b + k] = xyz[3 * k + 1];
      out[2][b + k] = xyz[3 * k + 2];
    }
  }
}

std::size_t FastWarpKernel::EvaluateInterleaved(const FastWarpPoints& points,
  float* xyz,
  const float* shift,
  std::size_t begin,
  std::size_t end) const
{
  const KernelPieces pc = PiecesOf(this->Start, this->End, this->Scale, this->Offset, this->Last);
  const KernelFunction kernel = KernelOf(this->Simd);
  const float zero[3] = { 0.0f, 0.0f, 0.0f };
  constexpr std::size_t chunk = 1 << 20;
  std::size_t bad = 0;
  for (std::size_t b = begin; b < end; b += chunk)
  {
    const int n = static_cast<int>(std::min(chunk, end - b));
    bad += static_cast<std::size_t>(kernel(this->Table.data(),
      pc,
      points.px + b,
      points.py + b,
      points.pz + b,
      points.s + b,
      points.f + b,
      xyz + 3 * b,
      shift ? shift : zero,
      n));
  }
  return bad;
}

void FastWarpLayout::Clear()
{
  for (auto* v : { &this->Ids, &this->Singles, &this->Pairs })
  {
    v->clear();
  }
  for (auto* v : { &this->Px, &this->Py, &this->Pz, &this->S, &this->F })
  {
    v->clear();
  }
}

template<typename T>
void FastWarpLayout::Build(const T* xyz,
  std::size_t n,
  const BoundPoint* records,
  const std::uint8_t* bound,
  const Vec3& origin,
  const ParallelFor& parallel)
{
  const ParallelFor serial =
    [](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
  { body(0, count); };
  const ParallelFor& parallelFor = parallel ? parallel : serial;
  this->Center = origin;
  // Fixed chunks (independent of the thread count): counts first, then each chunk writes its
  // points at its offsets, so the layout is the serial one whoever runs which chunk.
  const std::size_t chunkSize = std::max<std::size_t>(4096, (n + 255) / 256);
  const std::size_t chunks = (n + chunkSize - 1) / chunkSize;
  std::vector<std::size_t> boundCounts(chunks + 1, 0), pairCounts(chunks + 1, 0);
  parallelFor(chunks,
    [&](std::size_t c0, std::size_t c1)
    {
      for (std::size_t c = c0; c < c1; ++c)
      {
        std::size_t nb = 0, np = 0;
        // The flags alone (2: two projections, see WarpBinding::BindRange): the records are
        // read once, in the second pass.
        const std::size_t last = std::min(n, (c + 1) * chunkSize);
        for (std::size_t i = c * chunkSize; i < last; ++i)
        {
          nb += bound[i] != 0 ? 1 : 0;
          np += bound[i] == 2 ? 1 : 0;
        }
        boundCounts[c + 1] = nb;
        pairCounts[c + 1] = np;
      }
    });
  for (std::size_t c = 0; c < chunks; ++c)
  {
    boundCounts[c + 1] += boundCounts[c];
    pairCounts[c + 1] += pairCounts[c];
  }
  const std::size_t boundCount = boundCounts[chunks];
  const std::size_t pairCount = pairCounts[chunks];
  const std::size_t singleCount = boundCount - pairCount;
  this->Ids.resize(boundCount);
  this->Pairs.resize(pairCount);
  this->Singles.resize(singleCount);
  for (auto* v : { &this->Px, &this->Py, &this->Pz, &this->S, &this->F })
  {
    v->resize(singleCount);
  }
  std::int64_t* ids = this->Ids.data();
  std::int64_t* pairs = this->Pairs.data();
  std::int64_t* singles = this->Singles.data();
  float* px = this->Px.data();
  float* py = this->Py.data();
  float* pz = this->Pz.data();
  float* sv = this->S.data();
  float* fv = this->F.data();
  parallelFor(chunks,
    [&](std::size_t c0, std::size_t c1)
    {
      for (std::size_t c = c0; c < c1; ++c)
      {
        std::size_t k = boundCounts[c], p = pairCounts[c], m = k - p;
        for (std::size_t i = c * chunkSize; i < std::min(n, (c + 1) * chunkSize); ++i)
        {
          if (!bound[i])
          {
            continue;
          }
          const auto id = static_cast<std::int64_t>(i);
          ids[k++] = id;
          if (bound[i] == 2)
          {
            pairs[p++] = id;
            continue;
          }
          const BoundPoint& rec = records[i];
          const T* q = xyz + 3 * i;
          singles[m] = id;
          px[m] = static_cast<float>(static_cast<double>(q[0]) - origin.x);
          py[m] = static_cast<float>(static_cast<double>(q[1]) - origin.y);
          pz[m] = static_cast<float>(static_cast<double>(q[2]) - origin.z);
          sv[m] = static_cast<float>(std::clamp(rec.s0, 0.0, 1.0));
          fv[m] = static_cast<float>(rec.f);
          ++m;
        }
      }
    });
}

template<typename T>
std::size_t FastWarpLayout::EvaluateSingles(const FastWarpKernel& kernel,
  T* out,
  std::size_t begin,
  std::size_t end) const
{
  constexpr std::size_t block = 512;
  alignas(64) float xyz[3 * block];
  const float center[3] = { static_cast<float>(this->Center.x),
    static_cast<float>(this->Center.y),
    static_cast<float>(this->Center.z) };
  const FastWarpPoints all{
    this->Px.data(), this->Py.data(), this->Pz.data(), this->S.data(), this->F.data()
  };
  std::size_t bad = 0;
  for (std::size_t b = begin; b < end; b += block)
  {
    const std::size_t n = std::min(block, end - b);
    const std::int64_t* ids = this->Singles.data() + b;
    const FastWarpPoints points = all.From(b);
    // The ids increase, so a block without gaps is one contiguous run of the output: float
    // points are then written there directly, with the origin added by the kernel.
    if (std::is_same<T, float>::value && ids[n - 1] - ids[0] == static_cast<std::int64_t>(n - 1))
    {
      bad += kernel.EvaluateInterleaved(
        points, reinterpret_cast<float*>(out + 3 * ids[0]), center, 0, n);
      continue;
    }
    bad += kernel.EvaluateInterleaved(points, xyz, nullptr, 0, n);
    const T cx = static_cast<T>(this->Center.x);
    const T cy = static_cast<T>(this->Center.y);
    const T cz = static_cast<T>(this->Center.z);
    for (std::size_t k = 0; k < n; ++k)
    {
      T* o = out + 3 * ids[k];
      o[0] = cx + static_cast<T>(xyz[3 * k]);
      o[1] = cy + static_cast<T>(xyz[3 * k + 1]);
      o[2] = cz + static_cast<T>(xyz[3 * k + 2]);
    }
  }
  return bad;
}

// Built for the point types the filters warp (vtkPoints of float or double).
#define BENDER_FAST_WARP_LAYOUT_OF(T)                                                              \
  template void FastWarpLayout::Build<T>(const T*,                                                 \
    std::size_t,                                                                                   \
    const BoundPoint*,                                                                             \
    const std::uint8_t*,                                                                           \
    const Vec3&,                                                                                   \
    const ParallelFor&);                                                                           \
  template std::size_t FastWarpLayout::EvaluateSingles<T>(                                         \
    const FastWarpKernel&, T*, std::size_t, std::size_t) const
BENDER_FAST_WARP_LAYOUT_OF(float);
BENDER_FAST_WARP_LAYOUT_OF(double);
#undef BENDER_FAST_WARP_LAYOUT_OF

} // namespace bender
