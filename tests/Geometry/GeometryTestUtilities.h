#ifndef bender_GeometryTestUtilities_h
#define bender_GeometryTestUtilities_h

// Helpers shared by the geometry tests: random ribbons with fixed seeds, a minimal OFF
// reader for the conformance meshes (the Geometry module has no mesh I/O by design).

#include "Frame.h"
#include "Vec3.h"
#include "WarpPlan.h"

#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
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
  r.end.position = r.start.position + dir * (scale * (0.5 + std::uniform_real_distribution<>(0, 1)(rng)));
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

inline double MaxDeviation(const bender::Frame& a, const bender::Frame& b)
{
  double d = bender::Distance(a.origin, b.origin);
  d = std::max(d, bender::Distance(a.T, b.T));
  d = std::max(d, bender::Distance(a.N, b.N));
  d = std::max(d, bender::Distance(a.B, b.B));
  return d;
}

} // namespace bendertest

#endif
