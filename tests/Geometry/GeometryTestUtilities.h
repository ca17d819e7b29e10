#ifndef bender_GeometryTestUtilities_h
#define bender_GeometryTestUtilities_h

// Helpers shared by the geometry tests: random ribbons with fixed seeds, a minimal OFF
// reader for the conformance meshes (the Geometry module has no mesh I/O by design).

#include "Frame.h"
#include "Vec3.h"
#include "WarpPlan.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace bendertest
{
using bender::Vec3;

inline Vec3 RandomUnit(std::mt19937_64& rng)
{
  std::normal_distribution<double> g(0.0, 1.0);
  while (true)
  {
    const Vec3 v{ g(rng), g(rng), g(rng) };
    const double n = bender::Norm(v);
    if (n > 1e-3)
    {
      return v / n;
    }
  }
}

inline Vec3 RandomPoint(std::mt19937_64& rng, double scale)
{
  std::uniform_real_distribution<double> u(-scale, scale);
  return { u(rng), u(rng), u(rng) };
}

inline Vec3 RandomPerpendicular(std::mt19937_64& rng, const Vec3& t)
{
  while (true)
  {
    const Vec3 v = RandomUnit(rng);
    const Vec3 p = v - t * bender::Dot(v, t);
    if (bender::Norm(p) > 0.1)
    {
      return bender::Normalized(p);
    }
  }
}

/// A random ribbon with ends about `scale` apart, tangents roughly along the direction of
/// travel (so the wire stays well-conditioned), random normals and no extra turns.
inline bender::RibbonSpec RandomRibbon(std::mt19937_64& rng, double scale = 10.0)
{
  bender::RibbonSpec r;
  r.start.position = RandomPoint(rng, scale);
  const Vec3 dir = RandomUnit(rng);
  r.end.position =
    r.start.position + dir * (scale * (0.5 + std::uniform_real_distribution<>(0, 1)(rng)));
  r.start.tangent = bender::Normalized(dir + RandomUnit(rng) * 0.8);
  r.end.tangent = bender::Normalized(dir + RandomUnit(rng) * 0.8);
  r.start.normal = RandomPerpendicular(rng, r.start.tangent);
  r.end.normal = RandomPerpendicular(rng, r.end.tangent);
  return r;
}

struct Mesh
{
  std::vector<Vec3> points;
  std::vector<std::vector<int>> faces;
};

inline Mesh ReadOff(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
  {
    throw std::runtime_error(path + ": cannot open");
  }
  std::string magic;
  in >> magic;
  if (magic != "OFF")
  {
    throw std::runtime_error(path + ": not an OFF file");
  }
  std::size_t nv = 0, nf = 0, ne = 0;
  in >> nv >> nf >> ne;
  Mesh m;
  m.points.resize(nv);
  for (auto& p : m.points)
  {
    in >> p.x >> p.y >> p.z;
  }
  m.faces.resize(nf);
  for (auto& f : m.faces)
  {
    int n = 0;
    in >> n;
    f.resize(n);
    for (int& i : f)
    {
      in >> i;
    }
  }
  if (!in)
  {
    throw std::runtime_error(path + ": truncated");
  }
  return m;
}

constexpr double Pi = 3.14159265358979323846;

/// Wraps an angle to (-pi, pi].
inline double WrapAngle(double a)
{
  a = std::remainder(a, 2.0 * Pi);
  return a <= -Pi ? a + 2.0 * Pi : a;
}

inline double Uniform(std::mt19937_64& rng, double lo, double hi)
{
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

/// A rigid motion X -> Rot(axis, angle) X + t, built independently of the geometry core's
/// quaternions and screws.
struct Rigid
{
  Vec3 axis{ 1, 0, 0 };
  double angle = 0.0;
  Vec3 t;
  Vec3 Point(const Vec3& p) const { return bender::Rotate(axis, angle, p) + t; }
  Vec3 Vector(const Vec3& v) const { return bender::Rotate(axis, angle, v); }
};

inline Rigid RandomRigid(std::mt19937_64& rng, double scale = 10.0, double maxAngle = Pi)
{
  Rigid g;
  g.axis = RandomUnit(rng);
  g.angle = Uniform(rng, -maxAngle, maxAngle);
  g.t = RandomPoint(rng, scale);
  return g;
}

inline bender::RibbonEnd Transformed(const bender::RibbonEnd& e, const Rigid& g)
{
  return { g.Point(e.position), g.Vector(e.tangent), g.Vector(e.normal) };
}

inline bender::RibbonSpec Transformed(const bender::RibbonSpec& r, const Rigid& g)
{
  bender::RibbonSpec o = r;
  o.start = Transformed(r.start, g);
  o.end = Transformed(r.end, g);
  return o;
}

/// A ribbon with fully random tangents (may be invalid: callers catch InvalidRibbonError).
inline bender::RibbonSpec RandomWildRibbon(std::mt19937_64& rng, double scale = 10.0)
{
  bender::RibbonSpec r;
  r.start.position = RandomPoint(rng, scale);
  r.end.position = RandomPoint(rng, scale);
  r.start.tangent = RandomUnit(rng);
  r.end.tangent = RandomUnit(rng);
  r.start.normal = RandomPerpendicular(rng, r.start.tangent);
  r.end.normal = RandomPerpendicular(rng, r.end.tangent);
  return r;
}

/// Moves the ends of a ribbon by up to `move` and turns its tangents and normals by up to
/// `turn` radians about random axes.
inline bender::RibbonSpec Perturbed(std::mt19937_64& rng,
  const bender::RibbonSpec& r,
  double move,
  double turn)
{
  bender::RibbonSpec o = r;
  for (bender::RibbonEnd* e : { &o.start, &o.end })
  {
    e->position += RandomUnit(rng) * Uniform(rng, 0.0, move);
    const Vec3 k = RandomUnit(rng);
    const double a = Uniform(rng, -turn, turn);
    e->tangent = bender::Rotate(k, a, e->tangent);
    e->normal = bender::Rotate(k, a, e->normal);
    e->normal = bender::Rotate(e->tangent, Uniform(rng, -turn, turn), e->normal);
  }
  return o;
}

inline double Scale(const bender::RibbonSpec& r)
{
  return std::max({ 1.0, bender::Norm(r.start.position), bender::Norm(r.end.position) });
}

/// Distance from p to the line through a with unit direction k.
inline double DistanceToLine(const Vec3& p, const Vec3& a, const Vec3& k)
{
  return bender::Norm(bender::Cross(p - a, k));
}

/// An icosphere: the icosahedron subdivided `levels` times, projected on the sphere.
inline Mesh Icosphere(int levels, const Vec3& centre, double radius)
{
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v = { { -1, g, 0 },
    { 1, g, 0 },
    { -1, -g, 0 },
    { 1, -g, 0 },
    { 0, -1, g },
    { 0, 1, g },
    { 0, -1, -g },
    { 0, 1, -g },
    { g, 0, -1 },
    { g, 0, 1 },
    { -g, 0, -1 },
    { -g, 0, 1 } };
  std::vector<std::vector<int>> f = { { 0, 11, 5 },
    { 0, 5, 1 },
    { 0, 1, 7 },
    { 0, 7, 10 },
    { 0, 10, 11 },
    { 1, 5, 9 },
    { 5, 11, 4 },
    { 11, 10, 2 },
    { 10, 7, 6 },
    { 7, 1, 8 },
    { 3, 9, 4 },
    { 3, 4, 2 },
    { 3, 2, 6 },
    { 3, 6, 8 },
    { 3, 8, 9 },
    { 4, 9, 5 },
    { 2, 4, 11 },
    { 6, 2, 10 },
    { 8, 6, 7 },
    { 9, 8, 1 } };
  for (Vec3& p : v)
  {
    p = bender::Normalized(p);
  }
  for (int l = 0; l < levels; ++l)
  {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b)
    {
      const std::pair<int, int> key{ std::min(a, b), std::max(a, b) };
      auto it = mid.find(key);
      if (it != mid.end())
      {
        return it->second;
      }
      v.push_back(bender::Normalized(v[a] + v[b]));
      const int id = static_cast<int>(v.size()) - 1;
      mid[key] = id;
      return id;
    };
    std::vector<std::vector<int>> nf;
    for (const auto& t : f)
    {
      const int a = midpoint(t[0], t[1]);
      const int b = midpoint(t[1], t[2]);
      const int c = midpoint(t[2], t[0]);
      nf.push_back({ t[0], a, c });
      nf.push_back({ t[1], b, a });
      nf.push_back({ t[2], c, b });
      nf.push_back({ a, b, c });
    }
    f.swap(nf);
  }
  Mesh m;
  for (const Vec3& p : v)
  {
    m.points.push_back(centre + p * radius);
  }
  m.faces = f;
  return m;
}

inline bool FrameIsOrthonormalRightHanded(const bender::Frame& f, double tol)
{
  using bender::Dot;
  return std::abs(Dot(f.t, f.t) - 1) < tol && std::abs(Dot(f.n, f.n) - 1) < tol &&
    std::abs(Dot(f.b, f.b) - 1) < tol && std::abs(Dot(f.t, f.n)) < tol &&
    std::abs(Dot(f.t, f.b)) < tol && std::abs(Dot(f.n, f.b)) < tol &&
    std::abs(Dot(bender::Cross(f.t, f.n), f.b) - 1) < tol;
}

inline double MaxDeviation(const bender::Frame& a, const bender::Frame& b)
{
  double d = bender::Distance(a.origin, b.origin);
  d = std::max(d, bender::Distance(a.t, b.t));
  d = std::max(d, bender::Distance(a.n, b.n));
  d = std::max(d, bender::Distance(a.b, b.b));
  return d;
}

} // namespace bendertest

#endif
