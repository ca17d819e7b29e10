#include "FastWarpKernel.h"

#include <algorithm>
#include <cmath>

namespace bender
{

void FastWarpKernel::SetMotion(const MotionTable& table, const Vec3& origin)
{
  const std::vector<DualQuaternion>& src = table.Samples();
  const std::size_t n = src.size();
  this->Table.resize(8 * n);
  for (std::size_t j = 0; j < n; ++j)
  {
    // Conjugate by the translation to the origin: X_l -> R X_l + (R c + t - c).
    const DualQuaternion& m = src[j];
    const Vec3 t = (m.dual * Conjugate(m.real)).Vector() * 2.0;
    const Vec3 tl = RotateByQuaternion(m.real, origin) + t - origin;
    const Quaternion d = Quaternion{ 0.0, 0.5 * tl.x, 0.5 * tl.y, 0.5 * tl.z } * m.real;
    float* o = this->Table.data() + 8 * j;
    o[0] = static_cast<float>(m.real.w);
    o[1] = static_cast<float>(m.real.x);
    o[2] = static_cast<float>(m.real.y);
    o[3] = static_cast<float>(m.real.z);
    o[4] = static_cast<float>(d.w);
    o[5] = static_cast<float>(d.x);
    o[6] = static_cast<float>(d.y);
    o[7] = static_cast<float>(d.z);
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
constexpr float PiF = 3.14159265358979f;

// atan2(y, x) for y >= 0, about 1e-7 absolute (Cephes' atanf reduction).
BENDER_ALWAYS_INLINE float Atan2Pos(float y, float x)
{
  const float ax = std::fabs(x);
  const float mx = ax > y ? ax : y;
  const float mn = ax > y ? y : ax;
  float t = mn / mx;
  const bool big = t > 0.41421356f;
  t = big ? (t - 1.0f) / (t + 1.0f) : t;
  const float z = t * t;
  float a = (((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z -
              3.33329491539e-1f) *
      z * t +
    t;
  a = big ? a + 0.25f * PiF : a;
  a = ax > y ? a : 0.5f * PiF - a;
  return x < 0.0f ? PiF - a : a;
}

// sin and cos of phi in [0, pi], through x = phi - pi/2 in [-pi/2, pi/2] (Taylor, < 4e-8).
BENDER_ALWAYS_INLINE void SinCos(float phi, float& s, float& c)
{
  const float x = phi - 0.5f * PiF;
  const float x2 = x * x;
  const float sx = x *
    (1.0f +
      x2 *
        (-1.0f / 6.0f +
          x2 *
            (1.0f / 120.0f + x2 * (-1.0f / 5040.0f + x2 * (1.0f / 362880.0f - x2 / 39916800.0f)))));
  const float cx = 1.0f +
    x2 *
      (-0.5f +
        x2 *
          (1.0f / 24.0f +
            x2 * (-1.0f / 720.0f + x2 * (1.0f / 40320.0f + x2 * (-1.0f / 3628800.0f)))));
  s = cx;  // sin(phi) = cos(x)
  c = -sx; // cos(phi) = -sin(x)
}

#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define BENDER_TARGET_CLONES __attribute__((target_clones("arch=haswell", "default")))
#else
#define BENDER_TARGET_CLONES
#endif

// The pieces of the table as plain scalars so that the loop below stays branch-free.
struct KernelPieces
{
  float end0, end1;             // piece boundaries (2 where unused)
  float start0, start1, start2; // piece starts in s
  float scale0, scale1, scale2; // samples per unit s
  float first0, first1, first2; // index of each piece's first sample
  float span0, span1, span2;    // index of its last interval (samples - 2)
};

// Interpolates the table at each s of a block into SoA arrays (the table lookups are
// gathers, kept out of the arithmetic loop so that the latter vectorises).
constexpr int Block = 256;

struct BlockMotions
{
  alignas(64) float w[Block], vx[Block], vy[Block], vz[Block];
  alignas(64) float dw[Block], dx[Block], dy[Block], dz[Block];
};

void Interpolate(const float* table,
  const KernelPieces& pc,
  const float* sp,
  int n,
  BlockMotions& m)
{
  for (int k = 0; k < n; ++k)
  {
    // The uniform piece holding s (at most three, split at the junction parameters).
    const float sk = sp[k];
    float start = pc.start0, scale = pc.scale0, first = pc.first0, span = pc.span0;
    if (sk >= pc.end1)
    {
      start = pc.start2;
      scale = pc.scale2;
      first = pc.first2;
      span = pc.span2;
    }
    else if (sk >= pc.end0)
    {
      start = pc.start1;
      scale = pc.scale1;
      first = pc.first1;
      span = pc.span1;
    }
    const float u = std::max((sk - start) * scale, 0.0f);
    const float jl = std::min(static_cast<float>(static_cast<int>(u)), span);
    const float a = std::min(u - jl, 1.0f);
    const float b = 1.0f - a;
    const float* m0 = table + 8 * static_cast<int>(first + jl);
    const float* m1 = m0 + 8;
    m.w[k] = b * m0[0] + a * m1[0];
    m.vx[k] = b * m0[1] + a * m1[1];
    m.vy[k] = b * m0[2] + a * m1[2];
    m.vz[k] = b * m0[3] + a * m1[3];
    m.dw[k] = b * m0[4] + a * m1[4];
    m.dx[k] = b * m0[5] + a * m1[5];
    m.dy[k] = b * m0[6] + a * m1[6];
    m.dz[k] = b * m0[7] + a * m1[7];
  }
}

BENDER_TARGET_CLONES
void PowerAndApply(const BlockMotions& m,
  const float* px,
  const float* py,
  const float* pz,
  const float* fp,
  float* ox,
  float* oy,
  float* oz,
  int n)
{
#pragma omp simd
  for (int k = 0; k < n; ++k)
  {
    float w = m.w[k], vx = m.vx[k], vy = m.vy[k], vz = m.vz[k];
    float dw = m.dw[k], dx = m.dx[k], dy = m.dy[k], dz = m.dz[k];
    // Renormalise (DLB) and make the dual part orthogonal to the real part.
    const float inv = 1.0f / std::sqrt(w * w + vx * vx + vy * vy + vz * vz);
    w *= inv;
    vx *= inv;
    vy *= inv;
    vz *= inv;
    dw *= inv;
    dx *= inv;
    dy *= inv;
    dz *= inv;
    const float rd = w * dw + vx * dx + vy * dy + vz * dz;
    dw -= rd * w;
    dx -= rd * vx;
    dy -= rd * vy;
    dz -= rd * vz;
    // Power f of the screw: half angle h, rotation (cos fh, v sin fh / |v|), and the dual
    // part written without the axis direction so that it stays finite as |v| -> 0.
    const float f = fp[k];
    const float sv = std::sqrt(vx * vx + vy * vy + vz * vz);
    const float h = Atan2Pos(sv, w);
    float sphi, cphi;
    SinCos(f * h, sphi, cphi);
    const bool rotating = sv > 1e-6f;
    const float svSafe = rotating ? sv : 1.0f;
    const float rho = rotating ? sphi / svSafe : f;
    const float g = rotating ? (dw / (svSafe * svSafe)) * (rho * w - f * cphi) : 0.0f;
    const float rw = cphi;
    const float rx = rho * vx, ry = rho * vy, rz = rho * vz;
    const float Dw = f * dw * rho;
    const float Dx = rho * dx + g * vx, Dy = rho * dy + g * vy, Dz = rho * dz + g * vz;
    // t = 2 (D conj(r)).vec = 2 (-Dw rv + rw D - D x rv)
    const float tx = 2.0f * (-Dw * rx + rw * Dx - (Dy * rz - Dz * ry));
    const float ty = 2.0f * (-Dw * ry + rw * Dy - (Dz * rx - Dx * rz));
    const float tz = 2.0f * (-Dw * rz + rw * Dz - (Dx * ry - Dy * rx));
    // Rotate P by r: P + rw c + rv x c with c = 2 rv x P.
    const float x = px[k], y = py[k], z = pz[k];
    const float cx = 2.0f * (ry * z - rz * y);
    const float cy = 2.0f * (rz * x - rx * z);
    const float cz = 2.0f * (rx * y - ry * x);
    ox[k] = x + rw * cx + (ry * cz - rz * cy) + tx;
    oy[k] = y + rw * cy + (rz * cx - rx * cz) + ty;
    oz[k] = z + rw * cz + (rx * cy - ry * cx) + tz;
  }
}
} // namespace

void FastWarpKernel::Evaluate(const float* px,
  const float* py,
  const float* pz,
  const float* s,
  const float* f,
  float* ox,
  float* oy,
  float* oz,
  std::size_t begin,
  std::size_t end) const
{
  KernelPieces pc;
  pc.end0 = this->End[0];
  pc.end1 = this->End[1];
  pc.start0 = this->Start[0];
  pc.start1 = this->Start[1];
  pc.start2 = this->Start[2];
  pc.scale0 = this->Scale[0];
  pc.scale1 = this->Scale[1];
  pc.scale2 = this->Scale[2];
  pc.first0 = static_cast<float>(this->Offset[0]);
  pc.first1 = static_cast<float>(this->Offset[1]);
  pc.first2 = static_cast<float>(this->Offset[2]);
  pc.span0 = static_cast<float>(this->Last[0] - this->Offset[0] - 1);
  pc.span1 = static_cast<float>(this->Last[1] - this->Offset[1] - 1);
  pc.span2 = static_cast<float>(this->Last[2] - this->Offset[2] - 1);
  BlockMotions m;
  for (std::size_t b = begin; b < end; b += Block)
  {
    const int n = static_cast<int>(std::min<std::size_t>(Block, end - b));
    Interpolate(this->Table.data(), pc, s + b, n, m);
    PowerAndApply(m, px + b, py + b, pz + b, f + b, ox + b, oy + b, oz + b, n);
  }
}

void FastWarpLayout::Clear()
{
  for (auto* v : { &this->Ids, &this->Singles, &this->Pairs })
  {
    v->clear();
  }
  for (auto* v :
    { &this->Px, &this->Py, &this->Pz, &this->S, &this->F, &this->Ox, &this->Oy, &this->Oz })
  {
    v->clear();
  }
}

template<typename T>
void FastWarpLayout::Build(const T* xyz,
  std::size_t n,
  const BoundPoint* records,
  const std::uint8_t* bound,
  const Vec3& origin)
{
  this->Clear();
  this->Center = origin;
  const std::size_t expected =
    static_cast<std::size_t>(std::count(bound, bound + n, std::uint8_t(1)));
  this->Ids.reserve(expected);
  this->Singles.reserve(expected);
  for (auto* v : { &this->Px, &this->Py, &this->Pz, &this->S, &this->F })
  {
    v->reserve(expected);
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!bound[i])
    {
      continue;
    }
    const auto id = static_cast<std::int64_t>(i);
    this->Ids.push_back(id);
    const BoundPoint& rec = records[i];
    if (rec.lambda0 < 1.0)
    {
      this->Pairs.push_back(id);
      continue;
    }
    const T* p = xyz + 3 * i;
    this->Singles.push_back(id);
    this->Px.push_back(static_cast<float>(static_cast<double>(p[0]) - origin.x));
    this->Py.push_back(static_cast<float>(static_cast<double>(p[1]) - origin.y));
    this->Pz.push_back(static_cast<float>(static_cast<double>(p[2]) - origin.z));
    this->S.push_back(static_cast<float>(rec.s0));
    this->F.push_back(static_cast<float>(rec.f));
  }
  this->Ox.resize(this->Singles.size());
  this->Oy.resize(this->Singles.size());
  this->Oz.resize(this->Singles.size());
}

template<typename T>
std::size_t FastWarpLayout::EvaluateSingles(const FastWarpKernel& kernel,
  T* out,
  std::size_t begin,
  std::size_t end) const
{
  kernel.Evaluate(this->Px.data(),
    this->Py.data(),
    this->Pz.data(),
    this->S.data(),
    this->F.data(),
    this->Ox.data(),
    this->Oy.data(),
    this->Oz.data(),
    begin,
    end);
  std::size_t bad = 0;
  for (std::size_t k = begin; k < end; ++k)
  {
    T* o = out + 3 * this->Singles[k];
    o[0] = static_cast<T>(this->Center.x + this->Ox[k]);
    o[1] = static_cast<T>(this->Center.y + this->Oy[k]);
    o[2] = static_cast<T>(this->Center.z + this->Oz[k]);
    if (!std::isfinite(o[0]) || !std::isfinite(o[1]) || !std::isfinite(o[2]))
    {
      ++bad;
    }
  }
  return bad;
}

template void FastWarpLayout::Build<float>(const float*,
  std::size_t,
  const BoundPoint*,
  const std::uint8_t*,
  const Vec3&);
template void FastWarpLayout::Build<double>(const double*,
  std::size_t,
  const BoundPoint*,
  const std::uint8_t*,
  const Vec3&);
template std::size_t FastWarpLayout::EvaluateSingles<float>(const FastWarpKernel&,
  float*,
  std::size_t,
  std::size_t) const;
template std::size_t FastWarpLayout::EvaluateSingles<double>(const FastWarpKernel&,
  double*,
  std::size_t,
  std::size_t) const;

} // namespace bender
