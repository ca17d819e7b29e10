#include "ExactWarpKernel.h"

#include "FastWarpKernel.h"
#include "SimdMath.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace bender
{
namespace
{
using simd::Atan2;
using simd::SinCos;
constexpr int Lanes = ExactWarpKernel::Lanes;
using Block = ExactWarpKernel::Block;
using Path = ExactWarpKernel::Path;

// Orientation q (w x y z) and origin o of the frame of `P` at s (RibbonWarp::FramePath::At).
// Scalars only (no local arrays), so that the lanes of a simd loop stay in registers.
BENDER_SIMD_INLINE void FrameOf(const Path& P,
  double s,
  double& qw,
  double& qx,
  double& qy,
  double& qz,
  double& ox,
  double& oy,
  double& oz)
{
  const bool first = s <= P.sJ;
  const double u1 = s * P.invFirst;
  const double u2 = (s - P.sJ) * P.invSecond;
  const double u = first ? u1 : u2;
#define BENDER_PICK(field) (first ? P.field[0] : P.field[1])
  double ct, st, c2, s2;
  SinCos(0.5 * (P.tau * s + BENDER_PICK(twistOffset)), st, ct);
  const double half = 0.5 * BENDER_PICK(angle) * u;
  SinCos(half, s2, c2);
  const double tgx = first ? P.tangent[0][0] : P.tangent[1][0];
  const double tgy = first ? P.tangent[0][1] : P.tangent[1][1];
  const double tgz = first ? P.tangent[0][2] : P.tangent[1][2];
  const double bw = first ? P.base[0][0] : P.base[1][0];
  const double bx = first ? P.base[0][1] : P.base[1][1];
  const double by = first ? P.base[0][2] : P.base[1][2];
  const double bz = first ? P.base[0][3] : P.base[1][3];
  // twist = (ct, st T_a); a = twist * base; q = turn * a with turn = (c2, s2 n).
  const double tw = ct, tx = st * tgx, ty = st * tgy, tz = st * tgz;
  const double aw = tw * bw - tx * bx - ty * by - tz * bz;
  const double ax = tw * bx + tx * bw + ty * bz - tz * by;
  const double ay = tw * by - tx * bz + ty * bw + tz * bx;
  const double az = tw * bz + tx * by - ty * bx + tz * bw;
  const double nw = c2;
  const double nx = s2 * (first ? P.axis[0][0] : P.axis[1][0]);
  const double ny = s2 * (first ? P.axis[0][1] : P.axis[1][1]);
  const double nz = s2 * (first ? P.axis[0][2] : P.axis[1][2]);
  qw = nw * aw - nx * ax - ny * ay - nz * az;
  qx = nw * ax + nx * aw + ny * az - nz * ay;
  qy = nw * ay - nx * az + ny * aw + nz * ax;
  qz = nw * az + nx * ay - ny * ax + nz * aw;
  const double l = BENDER_PICK(length) * u;
#undef BENDER_PICK
  const double sinc = half > 0.0 ? s2 / (half > 0.0 ? half : 1.0) : 1.0;
  const double along = l * sinc * c2;
  const double across = l * sinc * s2;
  ox = (first ? P.start[0][0] : P.start[1][0]) + tgx * along +
    (first ? P.toCentre[0][0] : P.toCentre[1][0]) * across;
  oy = (first ? P.start[0][1] : P.start[1][1]) + tgy * along +
    (first ? P.toCentre[0][1] : P.toCentre[1][1]) * across;
  oz = (first ? P.start[0][2] : P.start[1][2]) + tgz * along +
    (first ? P.toCentre[0][2] : P.toCentre[1][2]) * across;
}

// The warp of one lane's point with the lifted motion at s (sign reference ref): the screw's
// fraction f applied to p (Screw.cxx's ApplyScrewFraction, branch-free).
BENDER_SIMD_INLINE void WarpAt(const Path& pi,
  const Path& pf,
  double s,
  double refw,
  double refx,
  double refy,
  double refz,
  double f,
  double x,
  double y,
  double z,
  double& outx,
  double& outy,
  double& outz)
{
  double iw, ix, iy, iz, oix, oiy, oiz, fw, fx, fy, fz, ofx, ofy, ofz;
  FrameOf(pi, s, iw, ix, iy, iz, oix, oiy, oiz);
  FrameOf(pf, s, fw, fx, fy, fz, ofx, ofy, ofz);
  // q = qf conj(qi), signed as the reference.
  double w = fw * iw + fx * ix + fy * iy + fz * iz;
  // Products that cancel when the frames are equal are paired, so that the identity comes out
  // exactly (v == 0, then a pure translation by exactly zero).
  double vx = (fx * iw - fw * ix) + (fz * iy - fy * iz);
  double vy = (fy * iw - fw * iy) + (fx * iz - fz * ix);
  double vz = (fz * iw - fw * iz) + (fy * ix - fx * iy);
  const bool flip = refw * w + refx * vx + refy * vy + refz * vz < 0.0;
  w = flip ? -w : w;
  vx = flip ? -vx : vx;
  vy = flip ? -vy : vy;
  vz = flip ? -vz : vz;
  // t = O' - R O (R O = O + w c + v x c, c = 2 v x O); dual = 1/2 (0, t) q.
  const double cx = 2.0 * (vy * oiz - vz * oiy);
  const double cy = 2.0 * (vz * oix - vx * oiz);
  const double cz = 2.0 * (vx * oiy - vy * oix);
  const double tx = ofx - (oix + w * cx + (vy * cz - vz * cy));
  const double ty = ofy - (oiy + w * cy + (vz * cx - vx * cz));
  const double tz = ofz - (oiz + w * cz + (vx * cy - vy * cx));
  const double dw = 0.5 * (-tx * vx - ty * vy - tz * vz);
  const double dx = 0.5 * (tx * w + ty * vz - tz * vy);
  const double dy = 0.5 * (-tx * vz + ty * w + tz * vx);
  const double dz = 0.5 * (tx * vy - ty * vx + tz * w);
  // Screw decomposition: h = atan2(|v|, w), K = v / |v|, pitch d, perpendicular part.
  const double sv = std::sqrt(vx * vx + vy * vy + vz * vz);
  const bool translation = !(sv > 0.0);
  const double svs = translation ? 1.0 : sv;
  const double h = Atan2(sv, w);
  const double inv = 1.0 / svs;
  const double kx = vx * inv, ky = vy * inv, kz = vz * inv;
  const double d = 2.0 * (w * (dx * kx + dy * ky + dz * kz) - dw * sv);
  const double px = dx - kx * (0.5 * d * w);
  const double py = dy - ky * (0.5 * d * w);
  const double pz = dz - kz * (0.5 * d * w);
  double sf, cf;
  SinCos(h * f, sf, cf);
  const double ratio = sf * inv;
  const double rw = cf, rx = sf * kx, ry = sf * ky, rz = sf * kz;
  const double e = 0.5 * f * d;
  const double uw = -e * sf;
  const double ux = kx * (e * cf) + px * ratio;
  const double uy = ky * (e * cf) + py * ratio;
  const double uz = kz * (e * cf) + pz * ratio;
  // t = 2 (u conj(r)).vec = 2 (-uw rv + rw u - u x rv)
  const double gx = 2.0 * (-uw * rx + rw * ux - (uy * rz - uz * ry));
  const double gy = 2.0 * (-uw * ry + rw * uy - (uz * rx - ux * rz));
  const double gz = 2.0 * (-uw * rz + rw * uz - (ux * ry - uy * rx));
  // Rotate p by r.
  const double ex = 2.0 * (ry * z - rz * y);
  const double ey = 2.0 * (rz * x - rx * z);
  const double ez = 2.0 * (rx * y - ry * x);
  const double mx = x + rw * ex + (ry * ez - rz * ey) + gx;
  const double my = y + rw * ey + (rz * ex - rx * ez) + gy;
  const double mz = z + rw * ez + (rx * ey - ry * ex) + gz;
  // A pure translation (|v| == 0): p + f t with t = 2 (dual conj(real)).vec.
  const double hx = 2.0 * (-dw * vx + w * dx - (dy * vz - dz * vy));
  const double hy = 2.0 * (-dw * vy + w * dy - (dz * vx - dx * vz));
  const double hz = 2.0 * (-dw * vz + w * dz - (dx * vy - dy * vx));
  const bool still = f == 0.0;
  outx = still ? x : (translation ? x + hx * f : mx);
  outy = still ? y : (translation ? y + hy * f : my);
  outz = still ? z : (translation ? z + hz * f : mz);
}

/// WarpAt for lane k of a block, with projection parameter s and the rotation r (r0 or r1).
BENDER_SIMD_INLINE void WarpLane(const Path& pi,
  const Path& pf,
  const Block& b,
  int k,
  double s,
  const double (&r)[4][Lanes],
  double& x,
  double& y,
  double& z)
{
  WarpAt(pi, pf, s, r[0][k], r[1][k], r[2][k], r[3][k], b.f[k], b.px[k], b.py[k], b.pz[k], x, y, z);
}

BENDER_SIMD_INLINE void RunBody(const Path* paths, Block& b, bool pairs)
{
  // Local copies: the stores into b cannot alias them, so their loads leave the loop and the
  // selects between the two pieces are between registers.
  const Path pi = paths[0];
  const Path pf = paths[1];
#pragma omp simd
  for (int k = 0; k < Lanes; ++k)
  {
    double x, y, z;
    WarpLane(pi, pf, b, k, b.s0[k], b.r0, x, y, z);
    b.ox[k] = x;
    b.oy[k] = y;
    b.oz[k] = z;
  }
  if (!pairs)
  {
    return;
  }
  // Points with two projections: both screws at the combined weight, averaged with lambda0.
#pragma omp simd
  for (int k = 0; k < Lanes; ++k)
  {
    double x, y, z;
    WarpLane(pi, pf, b, k, b.s1[k], b.r1, x, y, z);
    const double l0 = b.lambda0[k];
    const bool two = l0 < 1.0;
    b.ox[k] = two ? b.ox[k] * l0 + x * (1.0 - l0) : b.ox[k];
    b.oy[k] = two ? b.oy[k] * l0 + y * (1.0 - l0) : b.oy[k];
    b.oz[k] = two ? b.oz[k] * l0 + z * (1.0 - l0) : b.oz[k];
  }
}

using RunFunction = void (*)(const Path*, Block&, bool);

void RunBaseline(const Path* paths, Block& b, bool pairs)
{
  RunBody(paths, b, pairs);
}

#ifdef BENDER_SIMD_DISPATCH
BENDER_TARGET_AVX2 void RunAvx2(const Path* paths, Block& b, bool pairs)
{
  RunBody(paths, b, pairs);
}

BENDER_TARGET_AVX512 void RunAvx512(const Path* paths, Block& b, bool pairs)
{
  RunBody(paths, b, pairs);
}
#endif

RunFunction BestRun()
{
#ifdef BENDER_SIMD_DISPATCH
  switch (FastWarpKernel::BestLevel())
  {
    case FastWarpKernel::SimdLevel::Avx512:
      return RunAvx512;
    case FastWarpKernel::SimdLevel::Avx2:
      return RunAvx2;
    default:
      break;
  }
#endif
  return RunBaseline;
}

// One choice per process: every block of every thread runs the same code.
const RunFunction RunBlock = BestRun();

void CopyPath(const RibbonWarp::FramePath& from, Path& to)
{
  to.sJ = from.sJ;
  to.tau = from.tau;
  to.invFirst = from.sJ > 0.0 ? 1.0 / from.sJ : 0.0;
  to.invSecond = from.sJ < 1.0 ? 1.0 / (1.0 - from.sJ) : 0.0;
  for (int i = 0; i < 2; ++i)
  {
    const RibbonWarp::FramePath::Piece& piece = from.pieces[i];
    const Arc& arc = piece.arc;
    const Vec3 vectors[4] = {
      arc.start, arc.tangent, arc.line ? Vec3{} : arc.toCentre, arc.line ? Vec3{} : arc.axis
    };
    double(*targets[4])[3] = { &to.start[i], &to.tangent[i], &to.toCentre[i], &to.axis[i] };
    for (int v = 0; v < 4; ++v)
    {
      (*targets[v])[0] = vectors[v].x;
      (*targets[v])[1] = vectors[v].y;
      (*targets[v])[2] = vectors[v].z;
    }
    to.angle[i] = arc.line ? 0.0 : arc.angle;
    to.length[i] = arc.length;
    to.twistOffset[i] = piece.twistOffset;
    to.base[i][0] = piece.base.w;
    to.base[i][1] = piece.base.x;
    to.base[i][2] = piece.base.y;
    to.base[i][3] = piece.base.z;
  }
}
} // namespace

ExactWarpKernel::ExactWarpKernel(const RibbonWarp& warp)
  : Warp(warp)
{
  CopyPath(warp.InitialFrames(), this->Paths[0]);
  CopyPath(warp.FinalFrames(), this->Paths[1]);
}

void ExactWarpKernel::Fill(Block& b, int lane, const Vec3& p, const BoundPoint& rec) const
{
  const SampleGrid& grid = this->Warp.Grid();
  const std::vector<Quaternion>& lifted = this->Warp.LiftedRotations();
  b.px[lane] = p.x;
  b.py[lane] = p.y;
  b.pz[lane] = p.z;
  const double s0 = std::clamp(rec.s0, 0.0, 1.0);
  const double s1 = std::clamp(rec.s1, 0.0, 1.0);
  b.s0[lane] = s0;
  b.s1[lane] = s1;
  b.f[lane] = rec.f;
  b.lambda0[lane] = rec.lambda0;
  const Quaternion& q0 = lifted[grid.Nearest(s0)];
  const Quaternion& q1 = lifted[grid.Nearest(s1)];
  const double r0[4] = { q0.w, q0.x, q0.y, q0.z };
  const double r1[4] = { q1.w, q1.x, q1.y, q1.z };
  for (int c = 0; c < 4; ++c)
  {
    b.r0[c][lane] = r0[c];
    b.r1[c][lane] = r1[c];
  }
}

template<typename T>
std::size_t ExactWarpKernel::EvaluateRange(const WarpBatch<T>& batch,
  std::size_t begin,
  std::size_t end) const
{
  const T* in = batch.in;
  T* out = batch.out;
  const BoundPoint* records = batch.records;
  const std::int64_t* ids = batch.ids;
  Block b;
  std::size_t bad = 0;
  for (std::size_t first = begin; first < end; first += Lanes)
  {
    const int n = static_cast<int>(std::min<std::size_t>(Lanes, end - first));
    bool pairs = false;
    for (int lane = 0; lane < Lanes; ++lane)
    {
      // A short block repeats its first point: every lane computes something valid, and the
      // lanes in use compute exactly what they would in a full block.
      const std::int64_t i = ids[first + (lane < n ? lane : 0)];
      const T* q = in + 3 * i;
      const Vec3 p{
        static_cast<double>(q[0]), static_cast<double>(q[1]), static_cast<double>(q[2])
      };
      this->Fill(b, lane, p, records[i]);
      pairs = pairs || records[i].lambda0 < 1.0;
    }
    RunBlock(this->Paths, b, pairs);
    for (int lane = 0; lane < n; ++lane)
    {
      T* o = out + 3 * ids[first + lane];
      o[0] = static_cast<T>(b.ox[lane]);
      o[1] = static_cast<T>(b.oy[lane]);
      o[2] = static_cast<T>(b.oz[lane]);
      bad += std::isfinite(o[0]) && std::isfinite(o[1]) && std::isfinite(o[2]) ? 0 : 1;
    }
  }
  return bad;
}

Vec3 ExactWarpKernel::Apply(const Vec3& p, const BoundPoint& rec) const
{
  Block b;
  for (int lane = 0; lane < Lanes; ++lane)
  {
    this->Fill(b, lane, p, rec);
  }
  RunBlock(this->Paths, b, rec.lambda0 < 1.0);
  return { b.ox[0], b.oy[0], b.oz[0] };
}

template std::size_t ExactWarpKernel::EvaluateRange(const WarpBatch<float>&,
  std::size_t,
  std::size_t) const;
template std::size_t ExactWarpKernel::EvaluateRange(const WarpBatch<double>&,
  std::size_t,
  std::size_t) const;

} // namespace bender
