#include "vtkBenderCapFilter.h"

#include "BenderErrors.h"
#include "CapTriangulation.h"
#include "MeshTopology.h"
#include "PatchLabels.h"
#include "StringUtil.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
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
using bender::cap_detail::Cross2;
using bender::cap_detail::MinAngle2;
using bender::cap_detail::P2;
using bender::cap_detail::RimProblem;
using bender::cap_detail::Tri;
using bender::cap_detail::TriangulateCap;

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
    // vtkDelaunay2D is handed simple polygons only (a degenerate or self-overlapping rim makes
    // it read outside its arrays): a planar rim that is not one cannot be capped.
    const std::string rimProblem = RimProblem(loop.rim2);
    if (!rimProblem.empty())
    {
      const auto& first = x[static_cast<std::size_t>(loop.rim.front())];
      return fail("cannot cap the open end of " + std::to_string(loop.rim.size()) +
        " vertices from point " + std::to_string(loop.rim.front()) + " " +
        bender::FormatPoint({ { first[0], first[1], first[2] } }) + ": " + rimProblem);
    }
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
