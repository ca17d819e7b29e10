// CountInvertedTriangles: the flipped triangles of a warp (MeshCheckPasses.h).

#include "MeshCheckPasses.h"

#include "Vec3.h"

#include <vtkMath.h>
#include <vtkPolyData.h>
#include <vtkSMPThreadLocal.h>
#include <vtkSMPTools.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

namespace bender
{
namespace mesh_check
{

// Space inversion (paper 3.8) turns a piece of surface inside out: the warp is locally
// orientation-reversing, while a rigid motion, however large its rotation, is not. A triangle
// counts as flipped when
// - it lies on a fold: across one of its edges the two normals were within 60 degrees of each
//   other before the warp and more than 120 degrees apart after it; a continuous warp that
//   inverts space folds the surface along the border of the inverted region; or
// - its normal after the warp opposes the image of its normal before under the local
//   rotation, the best-fitting proper rotation (Kabsch) carrying the triangle and its
//   edge-neighbours' opposite vertices from before to after (a mirrored, curved neighbourhood
//   has no proper rotation fitting it). On a flat neighbourhood a mirror cannot be told from
//   a half turn, so this second test only adds what the first misses on curved surfaces.
vtkIdType CountInvertedTriangles(const std::vector<std::int64_t>& tris,
  const std::vector<std::uint8_t>& usable,
  vtkPolyData* before,
  const std::vector<Vec3>& after)
{
  const vtkIdType nt = static_cast<vtkIdType>(tris.size() / 3);
  // Across each edge of each usable triangle: the triangle on its other side (-1: none), from
  // the edges of the usable triangles (the others masked out of the edge list).
  std::vector<std::int64_t> masked(tris);
  for (vtkIdType t = 0; t < nt; ++t)
  {
    if (!usable[t])
    {
      masked[3 * t] = masked[3 * t + 1] = masked[3 * t + 2] = -1;
    }
  }
  const TriangleEdges edges(masked, static_cast<std::int64_t>(after.size()));
  std::vector<std::array<vtkIdType, 3>> across(static_cast<std::size_t>(nt), { { -1, -1, -1 } });
  const auto localEdge = [&](vtkIdType t, const MeshEdge& e)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t a = tris[3 * t + k], b = tris[3 * t + (k + 1) % 3];
      if (std::min(a, b) == e.lo && std::max(a, b) == e.hi)
      {
        return k;
      }
    }
    return 0;
  };
  std::vector<std::array<vtkIdType, 2>> pairs; // triangles sharing a manifold-like edge
  for (const MeshEdge& e : edges.Edges())
  {
    if (e.uses < 2)
    {
      continue;
    }
    const vtkIdType t = edges.Uses()[e.first].triangle;
    const vtkIdType u = edges.Uses()[e.first + 1].triangle;
    across[t][localEdge(t, e)] = u;
    across[u][localEdge(u, e)] = t;
    pairs.push_back({ { t, u } });
  }
  std::vector<Vec3> pre(static_cast<std::size_t>(before->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < before->GetNumberOfPoints(); ++i)
  {
    pre[i] = PointOf(before, i);
  }
  auto normal = [&](const std::vector<Vec3>& x, vtkIdType t)
  {
    const std::int64_t* v = &tris[3 * t];
    return Cross(x[v[1]] - x[v[0]], x[v[2]] - x[v[0]]);
  };
  std::vector<std::uint8_t> folded(static_cast<std::size_t>(nt), 0);
  for (const auto& [t, u] : pairs)
  {
    // A fold turns the angle between neighbouring normals from small to nearly 180 degrees;
    // a sharp but genuine bend of the surface does not come near that.
    const Vec3 bt = normal(pre, t), bu = normal(pre, u), at = normal(after, t),
               au = normal(after, u);
    const double nb = std::sqrt(Dot(bt, bt) * Dot(bu, bu));
    const double na = std::sqrt(Dot(at, at) * Dot(au, au));
    if (nb > 0.0 && na > 0.0 && Dot(bt, bu) > 0.5 * nb && Dot(at, au) < -0.5 * na)
    {
      folded[t] = folded[u] = 1;
    }
  }
  vtkIdType flipped = 0;
  for (vtkIdType t = 0; t < nt; ++t)
  {
    if (!usable[t])
    {
      continue;
    }
    if (folded[t])
    {
      ++flipped;
      continue;
    }
    std::vector<std::int64_t> ids(tris.begin() + 3 * t, tris.begin() + 3 * t + 3);
    for (int e = 0; e < 3; ++e)
    {
      const std::int64_t a = tris[3 * t + e], b = tris[3 * t + (e + 1) % 3];
      const vtkIdType u = across[t][e];
      if (u < 0)
      {
        continue;
      }
      for (int k = 0; k < 3; ++k)
      {
        const std::int64_t v = tris[3 * u + k];
        if (v != a && v != b)
        {
          ids.push_back(v);
        }
      }
    }
    // Kabsch: H = sum (p - cp)(q - cq)^T, R = V diag(1, 1, det) U^T.
    Vec3 cp, cq;
    for (std::int64_t v : ids)
    {
      cp += pre[v];
      cq += after[v];
    }
    cp = cp / static_cast<double>(ids.size());
    cq = cq / static_cast<double>(ids.size());
    double h[3][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } };
    for (std::int64_t v : ids)
    {
      for (int r = 0; r < 3; ++r)
      {
        for (int c = 0; c < 3; ++c)
        {
          h[r][c] += (pre[v][r] - cp[r]) * (after[v][c] - cq[c]);
        }
      }
    }
    double u[3][3], w[3], vt[3][3];
    vtkMath::SingularValueDecomposition3x3(h, u, w, vt);
    // vtkMath gives H = U W VT with rotations U and VT and signed singular values w; which of
    // them are negative varies (on a flat neighbourhood the smallest is +-1e-17, whatever the
    // sign of the others). With S = diag(sign w), H = (U S) |W| VT has non-negative values,
    // and the best proper rotation (Kabsch) is V D (U S)^T with D = diag(1, 1, det(V (U S)^T))
    // on the smallest value.
    double sign[3];
    int smallest = 0;
    for (int k = 0; k < 3; ++k)
    {
      sign[k] = w[k] < 0.0 ? -1.0 : 1.0;
      if (std::abs(w[k]) < std::abs(w[smallest]))
      {
        smallest = k;
      }
    }
    const double proper =
      vtkMath::Determinant3x3(u) * vtkMath::Determinant3x3(vt) * sign[0] * sign[1] * sign[2];
    sign[smallest] *= proper < 0.0 ? -1.0 : 1.0;
    double rot[3][3]; // R = V S U^T maps before to after
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        rot[r][c] = vt[0][r] * sign[0] * u[c][0] + vt[1][r] * sign[1] * u[c][1] +
          vt[2][r] * sign[2] * u[c][2];
      }
    }
    const std::int64_t* tv = &tris[3 * t];
    const Vec3 n0 = Cross(pre[tv[1]] - pre[tv[0]], pre[tv[2]] - pre[tv[0]]);
    const Vec3 n1 = Cross(after[tv[1]] - after[tv[0]], after[tv[2]] - after[tv[0]]);
    const auto row = [&](int r) { return rot[r][0] * n0.x + rot[r][1] * n0.y + rot[r][2] * n0.z; };
    const Vec3 rn0(row(0), row(1), row(2));
    if (Dot(rn0, n1) < 0)
    {
      ++flipped;
    }
  }
  return flipped;
}

} // namespace mesh_check
} // namespace bender
