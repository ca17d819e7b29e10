#include "vtkBenderCapFilter.h"

#include "BenderErrors.h"
#include "MeshTopology.h"
#include "PatchLabels.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDelaunay2D.h"
#include "vtkIdList.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <vector>

vtkStandardNewMacro(vtkBenderCapFilter);

namespace
{
using P2 = std::array<double, 2>;
using Tri = std::array<int, 3>;

double Cross2(const P2& o, const P2& a, const P2& b)
{
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

bool InsidePolygon(const std::vector<P2>& poly, const P2& p)
{
  bool inside = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
  {
    const P2& a = poly[i];
    const P2& b = poly[j];
    if ((a[1] > p[1]) != (b[1] > p[1]) &&
      p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0])
    {
      inside = !inside;
    }
  }
  return inside;
}

double SegmentDistance(const P2& p, const P2& a, const P2& b)
{
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const double ex = a[0] + t * dx - p[0], ey = a[1] + t * dy - p[1];
  return std::sqrt(ex * ex + ey * ey);
}

/// Smallest angle of a triangle, degrees (0 for a degenerate one).
double MinAngle2(const P2& a, const P2& b, const P2& c)
{
  const P2* v[3] = { &a, &b, &c };
  double best = 180.0;
  for (int k = 0; k < 3; ++k)
  {
    const P2& o = *v[k];
    const P2& p = *v[(k + 1) % 3];
    const P2& q = *v[(k + 2) % 3];
    const double ux = p[0] - o[0], uy = p[1] - o[1], wx = q[0] - o[0], wy = q[1] - o[1];
    const double nu = std::hypot(ux, uy), nw = std::hypot(wx, wy);
    if (nu <= 0 || nw <= 0)
    {
      return 0.0;
    }
    const double cosine = std::clamp((ux * wx + uy * wy) / (nu * nw), -1.0, 1.0);
    best = std::min(best, std::acos(cosine) * 180.0 / M_PI);
  }
  return best;
}

/// Constrained Delaunay triangulation of the counter-clockwise rim polygon (ids 0..m-1) and
/// the interior points (ids m..), counter-clockwise triangles. Empty when the triangulation
/// does not cover the polygon exactly (a rim edge missing, a triangle outside, a point unused).
std::vector<Tri> ConstrainedDelaunay(const std::vector<P2>& rim, const std::vector<P2>& interior)
{
  const int m = static_cast<int>(rim.size());
  const int n = m + static_cast<int>(interior.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const P2& p : rim)
  {
    points->InsertNextPoint(p[0], p[1], 0.0);
  }
  for (const P2& p : interior)
  {
    points->InsertNextPoint(p[0], p[1], 0.0);
  }
  vtkNew<vtkPolyData> input;
  input->SetPoints(points);
  vtkNew<vtkCellArray> boundary;
  boundary->InsertNextCell(m);
  for (int i = 0; i < m; ++i)
  {
    boundary->InsertCellPoint(i);
  }
  vtkNew<vtkPolyData> source;
  source->SetPoints(points);
  source->SetPolys(boundary);
  vtkNew<vtkDelaunay2D> delaunay;
  delaunay->SetInputData(input);
  delaunay->SetSourceData(source);
  delaunay->SetTolerance(1e-12);
  delaunay->SetProjectionPlaneMode(VTK_DELAUNAY_XY_PLANE);
  delaunay->BoundingTriangulationOff();
  delaunay->Update();
  vtkPolyData* out = delaunay->GetOutput();
  std::vector<Tri> tris;
  if (out->GetNumberOfPoints() != n)
  {
    return {};
  }
  std::vector<P2> all(rim);
  all.insert(all.end(), interior.begin(), interior.end());
  std::set<std::pair<int, int>> edges;
  std::vector<char> used(static_cast<std::size_t>(n), 0);
  vtkIdType npts;
  const vtkIdType* pts;
  vtkCellArray* polys = out->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(npts, pts);)
  {
    if (npts != 3)
    {
      return {};
    }
    Tri t{ { static_cast<int>(pts[0]), static_cast<int>(pts[1]), static_cast<int>(pts[2]) } };
    const double area = Cross2(all[t[0]], all[t[1]], all[t[2]]);
    if (area == 0.0)
    {
      return {};
    }
    if (area < 0)
    {
      std::swap(t[1], t[2]);
    }
    const P2 centroid{ { (all[t[0]][0] + all[t[1]][0] + all[t[2]][0]) / 3.0,
      (all[t[0]][1] + all[t[1]][1] + all[t[2]][1]) / 3.0 } };
    if (!InsidePolygon(rim, centroid))
    {
      return {};
    }
    for (int k = 0; k < 3; ++k)
    {
      edges.insert({ t[k], t[(k + 1) % 3] });
      used[static_cast<std::size_t>(t[k])] = 1;
    }
    tris.push_back(t);
  }
  // A triangulation of a polygon with m rim and k interior points has m + 2k - 2 triangles.
  if (static_cast<int>(tris.size()) != m + 2 * (n - m) - 2 ||
    std::count(used.begin(), used.end(), 0) != 0)
  {
    return {};
  }
  for (int i = 0; i < m; ++i)
  {
    if (!edges.count({ i, (i + 1) % m }))
    {
      return {};
    }
  }
  return tris;
}

/// The cap of a counter-clockwise rim: interior points and counter-clockwise triangles.
/// False when no triangulation covers the rim.
bool TriangulateCap(const std::vector<P2>& rim, std::vector<P2>& interior, std::vector<Tri>& tris)
{
  const std::size_t m = rim.size();
  double h = 0.0;
  double lo[2] = { rim[0][0], rim[0][1] }, hi[2] = { rim[0][0], rim[0][1] };
  for (std::size_t i = 0; i < m; ++i)
  {
    h += std::hypot(rim[(i + 1) % m][0] - rim[i][0], rim[(i + 1) % m][1] - rim[i][1]);
    for (int a = 0; a < 2; ++a)
    {
      lo[a] = std::min(lo[a], rim[i][a]);
      hi[a] = std::max(hi[a], rim[i][a]);
    }
  }
  h /= static_cast<double>(m);
  for (const double margin : { 0.6, 0.9 })
  {
    // A triangular lattice of spacing h through the origin (the rim's centroid).
    interior.clear();
    const double dy = h * std::sqrt(3.0) / 2.0;
    const long j0 = static_cast<long>(std::floor(lo[1] / dy)) - 1;
    const long j1 = static_cast<long>(std::ceil(hi[1] / dy)) + 1;
    const long i0 = static_cast<long>(std::floor(lo[0] / h)) - 1;
    const long i1 = static_cast<long>(std::ceil(hi[0] / h)) + 1;
    for (long j = j0; j <= j1; ++j)
    {
      for (long i = i0; i <= i1; ++i)
      {
        const P2 p{ { (static_cast<double>(i) + ((j % 2) != 0 ? 0.5 : 0.0)) * h,
          static_cast<double>(j) * dy } };
        if (!InsidePolygon(rim, p))
        {
          continue;
        }
        bool farEnough = true;
        for (std::size_t k = 0; k < m && farEnough; ++k)
        {
          farEnough = SegmentDistance(p, rim[k], rim[(k + 1) % m]) >= margin * h;
        }
        if (farEnough)
        {
          interior.push_back(p);
        }
      }
    }
    tris = ConstrainedDelaunay(rim, interior);
    if (tris.empty())
    {
      continue;
    }
    // Laplacian smoothing of the interior points, each pass followed by a new triangulation;
    // a pass whose triangulation fails is dropped.
    for (int pass = 0; pass < 3; ++pass)
    {
      std::vector<std::set<int>> neighbours(m + interior.size());
      for (const Tri& t : tris)
      {
        for (int k = 0; k < 3; ++k)
        {
          neighbours[t[k]].insert(t[(k + 1) % 3]);
          neighbours[t[k]].insert(t[(k + 2) % 3]);
        }
      }
      std::vector<P2> moved(interior);
      for (std::size_t q = 0; q < interior.size(); ++q)
      {
        const auto& around = neighbours[m + q];
        P2 mean{ { 0, 0 } };
        for (int v : around)
        {
          const P2& p = v < static_cast<int>(m) ? rim[v] : interior[v - m];
          mean[0] += p[0] / static_cast<double>(around.size());
          mean[1] += p[1] / static_cast<double>(around.size());
        }
        if (!around.empty() && InsidePolygon(rim, mean))
        {
          moved[q] = mean;
        }
      }
      std::vector<Tri> retriangulated = ConstrainedDelaunay(rim, moved);
      if (retriangulated.empty())
      {
        break;
      }
      interior = moved;
      tris = retriangulated;
    }
    return true;
  }
  // Last resort: the rim alone.
  interior.clear();
  tris = ConstrainedDelaunay(rim, interior);
  return !tris.empty();
}

struct Loop
{
  std::vector<vtkIdType> rim;
  double centre[3];
  double normal[3]; // the loop runs counter-clockwise about it
  double e1[3], e2[3];
  std::vector<P2> rim2;
  std::vector<P2> interior;
  std::vector<Tri> tris;
  double area = 0.0;
  double maxRimDistance = 0.0;
};
} // namespace

void vtkBenderCapFilter::AddCapName(const double point[3], const std::string& name, bool inlet)
{
  this->Names.push_back(CapName{ { { point[0], point[1], point[2] } }, name, inlet });
  this->Modified();
}

void vtkBenderCapFilter::ClearCapNames()
{
  this->Names.clear();
  this->Modified();
}

int vtkBenderCapFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->LastError.clear();
  this->Caps.clear();
  this->NumberOfSkippedLoops = 0;
  auto fail = [this, output](const std::string& message)
  {
    this->LastError = message;
    this->Caps.clear();
    if (output)
    {
      output->Initialize();
    }
    vtkErrorMacro(<< message);
    return 0;
  };
  if (!input || !output)
  {
    return fail("no input surface");
  }
  {
    std::set<std::string> seen;
    int inlets = 0;
    for (const CapName& entry : this->Names)
    {
      if (!bender::IsValidPatchName(entry.name) || entry.name == "wall")
      {
        return fail("invalid cap name '" + entry.name +
          "': use letters, digits and '_', not starting with a digit, not 'wall'");
      }
      if (!seen.insert(entry.name).second)
      {
        return fail("the cap name '" + entry.name + "' is given twice");
      }
      inlets += entry.inlet ? 1 : 0;
    }
    if (inlets > 1)
    {
      return fail("more than one cap is marked as the inlet");
    }
  }
  const vtkIdType n0 = input->GetNumberOfPoints();
  std::vector<std::array<double, 3>> x(static_cast<std::size_t>(n0));
  for (vtkIdType i = 0; i < n0; ++i)
  {
    input->GetPoint(i, x[i].data());
    if (!std::isfinite(x[i][0]) || !std::isfinite(x[i][1]) || !std::isfinite(x[i][2]))
    {
      return fail("the input surface has non-finite (NaN or infinite) point coordinates");
    }
  }
  // Triangles and the input cell each comes from (cells are verts, lines, polys, strips).
  const std::vector<std::int64_t> tris = bender::CollectTriangles(input);
  std::vector<vtkIdType> source;
  {
    vtkIdType cell = input->GetNumberOfVerts() + input->GetNumberOfLines();
    vtkIdType npts;
    const vtkIdType* pts;
    for (input->GetPolys()->InitTraversal(); input->GetPolys()->GetNextCell(npts, pts); ++cell)
    {
      source.insert(source.end(), static_cast<std::size_t>(std::max<vtkIdType>(0, npts - 2)), cell);
    }
    for (input->GetStrips()->InitTraversal(); input->GetStrips()->GetNextCell(npts, pts); ++cell)
    {
      source.insert(source.end(), static_cast<std::size_t>(std::max<vtkIdType>(0, npts - 2)), cell);
    }
  }

  // Directed boundary loops: each boundary edge (a -> b) as its only triangle runs it. Only
  // closed loops of at least 3 vertices are capped; the others are counted as skipped.
  std::vector<Loop> loops;
  for (const bender::BoundaryChain& chain : bender::BoundaryLoops(tris, n0))
  {
    if (!chain.closed || chain.vertices.size() < 3)
    {
      ++this->NumberOfSkippedLoops;
      continue;
    }
    Loop loop;
    loop.rim.assign(chain.vertices.begin(), chain.vertices.end());
    // Least-squares plane: centroid and the smallest eigenvector of the covariance.
    double* c = loop.centre;
    c[0] = c[1] = c[2] = 0.0;
    const double m = static_cast<double>(loop.rim.size());
    for (vtkIdType v : loop.rim)
    {
      for (int a = 0; a < 3; ++a)
      {
        c[a] += x[v][a] / m;
      }
    }
    double cov[3][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } };
    double diameter = 0.0;
    for (vtkIdType v : loop.rim)
    {
      for (int a = 0; a < 3; ++a)
      {
        for (int b = 0; b < 3; ++b)
        {
          cov[a][b] += (x[v][a] - c[a]) * (x[v][b] - c[b]);
        }
      }
      diameter =
        std::max(diameter, 2.0 * std::sqrt(vtkMath::Distance2BetweenPoints(x[v].data(), c)));
    }
    double* rows[3] = { cov[0], cov[1], cov[2] };
    double eigen[3], vec0[3], vec1[3], vec2[3];
    double* vecs[3] = { vec0, vec1, vec2 };
    vtkMath::Jacobi(rows, eigen, vecs);
    // Eigenvalues sorted decreasing; columns of vecs are eigenvectors.
    for (int a = 0; a < 3; ++a)
    {
      loop.e1[a] = vecs[a][0];
      loop.e2[a] = vecs[a][1];
    }
    vtkMath::Cross(loop.e1, loop.e2, loop.normal);
    vtkMath::Normalize(loop.normal);
    for (vtkIdType v : loop.rim)
    {
      const double d[3] = { x[v][0] - c[0], x[v][1] - c[1], x[v][2] - c[2] };
      loop.maxRimDistance = std::max(loop.maxRimDistance, std::abs(vtkMath::Dot(d, loop.normal)));
      loop.rim2.push_back(P2{ { vtkMath::Dot(d, loop.e1), vtkMath::Dot(d, loop.e2) } });
    }
    if (loop.maxRimDistance > this->Planarity * diameter)
    {
      ++this->NumberOfSkippedLoops;
      continue;
    }
    // Counter-clockwise about the normal.
    double twiceArea = 0.0;
    for (std::size_t i = 0; i < loop.rim2.size(); ++i)
    {
      const P2& a = loop.rim2[i];
      const P2& b = loop.rim2[(i + 1) % loop.rim2.size()];
      twiceArea += a[0] * b[1] - a[1] * b[0];
    }
    if (twiceArea < 0)
    {
      for (int a = 0; a < 3; ++a)
      {
        loop.e2[a] = -loop.e2[a];
        loop.normal[a] = -loop.normal[a];
      }
      for (P2& p : loop.rim2)
      {
        p[1] = -p[1];
      }
    }
    loop.area = 0.5 * std::abs(twiceArea);
    if (!TriangulateCap(loop.rim2, loop.interior, loop.tris))
    {
      ++this->NumberOfSkippedLoops;
      continue;
    }
    loops.push_back(std::move(loop));
  }
  // Ids by decreasing area, ties by the smallest rim vertex.
  std::sort(loops.begin(),
    loops.end(),
    [](const Loop& a, const Loop& b)
    {
      if (a.area != b.area)
      {
        return a.area > b.area;
      }
      return *std::min_element(a.rim.begin(), a.rim.end()) <
        *std::min_element(b.rim.begin(), b.rim.end());
    });

  // Labels already on the input (a labelled surface capped again) are kept: its patches keep
  // their ids, names and types, and the new caps come after them.
  std::vector<int> inputIds;
  std::vector<bender::PatchLabel> inputPatches;
  if (bender::HasPatchLabels(input))
  {
    try
    {
      inputIds = bender::CellPatchIds(input);
      inputPatches = bender::ReadPatchLabels(input);
    }
    catch (const bender::Error& e)
    {
      return fail(e.what());
    }
  }
  int firstCapId = 2;
  bool inputHasInlet = false;
  for (const bender::PatchLabel& label : inputPatches)
  {
    firstCapId = std::max(firstCapId, label.id + 1);
    inputHasInlet = inputHasInlet || label.type == bender::PatchType::Inlet;
  }

  // Names: by position, then the defaults for the others.
  std::vector<std::string> names(loops.size());
  int inlet = loops.empty() || inputHasInlet ? -1 : 0;
  for (const CapName& entry : this->Names)
  {
    if (loops.empty())
    {
      break;
    }
    std::size_t best = 0;
    for (std::size_t k = 1; k < loops.size(); ++k)
    {
      if (vtkMath::Distance2BetweenPoints(entry.point.data(), loops[k].centre) <
        vtkMath::Distance2BetweenPoints(entry.point.data(), loops[best].centre))
      {
        best = k;
      }
    }
    if (!names[best].empty())
    {
      const double* c = loops[best].centre;
      return fail("the cap names '" + names[best] + "' and '" + entry.name +
        "' both point at the cap centred at (" + std::to_string(c[0]) + ", " +
        std::to_string(c[1]) + ", " + std::to_string(c[2]) + ")");
    }
    names[best] = entry.name;
    if (entry.inlet)
    {
      inlet = static_cast<int>(best);
    }
  }
  {
    std::set<std::string> taken(names.begin(), names.end());
    for (const bender::PatchLabel& label : inputPatches)
    {
      if (taken.count(label.name))
      {
        return fail("the cap name '" + label.name + "' is already the name of patch " +
          std::to_string(label.id) + " of the input");
      }
      taken.insert(label.name);
    }
    int next = 1;
    for (std::size_t k = 0; k < loops.size(); ++k)
    {
      if (!names[k].empty())
      {
        continue;
      }
      if (static_cast<int>(k) == inlet && !taken.count("inlet"))
      {
        names[k] = "inlet";
      }
      else
      {
        std::string name;
        do
        {
          name = "outlet_" + std::to_string(next++);
        } while (taken.count(name));
        names[k] = name;
      }
      taken.insert(names[k]);
    }
  }

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const auto& p : x)
  {
    points->InsertNextPoint(p.data());
  }
  std::vector<std::array<vtkIdType, 3>> cells;
  std::vector<int> ids;
  for (std::size_t t = 0; t < tris.size(); t += 3)
  {
    cells.push_back({ { tris[t], tris[t + 1], tris[t + 2] } });
    ids.push_back(
      inputIds.empty() ? bender::kWallEntityId : inputIds[static_cast<std::size_t>(source[t / 3])]);
  }
  const vtkIdType wallTriangles = static_cast<vtkIdType>(cells.size());

  vtkPointData* inPD = input->GetPointData();
  vtkNew<vtkPointData> pd;
  pd->CopyNormalsOff();
  pd->InterpolateAllocate(inPD, n0);
  for (vtkIdType i = 0; i < n0; ++i)
  {
    pd->CopyData(inPD, i, i);
  }
  for (std::size_t k = 0; k < loops.size(); ++k)
  {
    Loop& loop = loops[k];
    const int id = static_cast<int>(k) + firstCapId;
    const double* c = loop.centre;
    if (this->ProjectRim)
    {
      for (vtkIdType v : loop.rim)
      {
        double p[3];
        points->GetPoint(v, p);
        const double d[3] = { p[0] - c[0], p[1] - c[1], p[2] - c[2] };
        const double off = vtkMath::Dot(d, loop.normal);
        for (int a = 0; a < 3; ++a)
        {
          p[a] -= off * loop.normal[a];
        }
        points->SetPoint(v, p);
      }
    }
    vtkNew<vtkIdList> rimIds;
    for (vtkIdType v : loop.rim)
    {
      rimIds->InsertNextId(v);
    }
    std::vector<double> weights(loop.rim.size(), 1.0 / static_cast<double>(loop.rim.size()));
    std::vector<vtkIdType> pointOf(loop.rim.begin(), loop.rim.end());
    for (const P2& q : loop.interior)
    {
      const double p[3] = { c[0] + q[0] * loop.e1[0] + q[1] * loop.e2[0],
        c[1] + q[0] * loop.e1[1] + q[1] * loop.e2[1],
        c[2] + q[0] * loop.e1[2] + q[1] * loop.e2[2] };
      const vtkIdType id3 = points->InsertNextPoint(p);
      pd->InterpolatePoint(inPD, id3, rimIds, weights.data());
      pointOf.push_back(id3);
    }
    CapInfo info;
    info.id = id;
    info.name = names[k];
    info.inlet = static_cast<int>(k) == inlet;
    info.rimPoints = static_cast<int>(loop.rim.size());
    info.maxRimDistance = loop.maxRimDistance;
    info.minAngle = 180.0;
    info.minInteriorAngle = 180.0;
    const int m = static_cast<int>(loop.rim.size());
    double centroid[2] = { 0, 0 };
    double area = 0.0;
    for (const Tri& t : loop.tris)
    {
      auto at = [&](int v) -> const P2& { return v < m ? loop.rim2[v] : loop.interior[v - m]; };
      const double angle = MinAngle2(at(t[0]), at(t[1]), at(t[2]));
      info.minAngle = std::min(info.minAngle, angle);
      if (t[0] >= m && t[1] >= m && t[2] >= m)
      {
        info.minInteriorAngle = std::min(info.minInteriorAngle, angle);
      }
      const double a = 0.5 * Cross2(at(t[0]), at(t[1]), at(t[2]));
      area += a;
      for (int e = 0; e < 2; ++e)
      {
        centroid[e] += a * (at(t[0])[e] + at(t[1])[e] + at(t[2])[e]) / 3.0;
      }
      // Counter-clockwise in the plane: the cap runs the rim the other way from the wall.
      cells.push_back({ { pointOf[t[0]], pointOf[t[2]], pointOf[t[1]] } });
      ids.push_back(id);
    }
    if (info.minInteriorAngle == 180.0)
    {
      info.minInteriorAngle = 0.0;
    }
    info.area = area;
    info.radius = std::sqrt(area / M_PI);
    for (int a = 0; a < 3; ++a)
    {
      info.centre[a] = c[a] + (centroid[0] * loop.e1[a] + centroid[1] * loop.e2[a]) / area;
      info.normal[a] = -loop.normal[a];
    }
    this->Caps.push_back(info);
  }

  // Outwards: a closed output with a negative signed volume is reversed.
  if (this->NumberOfSkippedLoops == 0 && !cells.empty())
  {
    const std::vector<std::int64_t> all = [&cells]()
    {
      std::vector<std::int64_t> flat;
      for (const auto& t : cells)
      {
        flat.insert(flat.end(), t.begin(), t.end());
      }
      return flat;
    }();
    if (bender::BoundaryLoops(all, points->GetNumberOfPoints()).empty())
    {
      double volume = 0.0;
      for (const auto& t : cells)
      {
        double a[3], b[3], c[3], bc[3];
        points->GetPoint(t[0], a);
        points->GetPoint(t[1], b);
        points->GetPoint(t[2], c);
        vtkMath::Cross(b, c, bc);
        volume += vtkMath::Dot(a, bc) / 6.0;
      }
      if (volume < 0)
      {
        for (auto& t : cells)
        {
          std::swap(t[1], t[2]);
        }
        for (CapInfo& info : this->Caps)
        {
          for (double& v : info.normal)
          {
            v = -v;
          }
        }
      }
    }
  }

  vtkNew<vtkCellArray> polys;
  for (const auto& t : cells)
  {
    polys->InsertNextCell(3, t.data());
  }
  output->Initialize();
  output->SetPoints(points);
  output->SetPolys(polys);
  output->GetPointData()->ShallowCopy(pd);
  vtkCellData* outCD = output->GetCellData();
  vtkCellData* inCD = input->GetCellData();
  outCD->CopyNormalsOff();
  const vtkIdType total = polys->GetNumberOfCells();
  outCD->CopyAllocate(inCD, total);
  for (vtkIdType t = 0; t < wallTriangles; ++t)
  {
    outCD->CopyData(inCD, source[t], t);
  }
  for (int a = 0; a < outCD->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = outCD->GetAbstractArray(a);
    array->SetNumberOfTuples(total);
    if (auto* data = vtkDataArray::SafeDownCast(array))
    {
      for (vtkIdType t = wallTriangles; t < total; ++t)
      {
        for (int k = 0; k < data->GetNumberOfComponents(); ++k)
        {
          data->SetComponent(t, k, 0.0);
        }
      }
    }
  }
  std::vector<bender::PatchLabel> patches = inputPatches;
  if (patches.empty() || patches.front().id != bender::kWallEntityId)
  {
    patches.insert(patches.begin(), { bender::kWallEntityId, "wall", bender::PatchType::Wall });
  }
  for (const CapInfo& info : this->Caps)
  {
    patches.push_back(
      { info.id, info.name, info.inlet ? bender::PatchType::Inlet : bender::PatchType::Outlet });
  }
  try
  {
    bender::WritePatchLabels(output, ids, patches);
  }
  catch (const bender::Error& e)
  {
    return fail(e.what());
  }
  return 1;
}

void vtkBenderCapFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Planarity: " << this->Planarity << "\n";
  os << indent << "ProjectRim: " << this->ProjectRim << "\n";
  os << indent << "CapNames: " << this->Names.size() << "\n";
  os << indent << "NumberOfCaps: " << this->Caps.size() << "\n";
}
