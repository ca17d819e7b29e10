#include "CenterlinePasses.h"

#include "StringUtil.h"
#include "UnionFind.h"
#include "Vec3.h"
#include "VesselArrayNames.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>

namespace bender
{
namespace centerline
{
namespace
{

void AppendSamples(const PathSamples& path,
  std::size_t from,
  std::size_t to,
  vtkPoints* points,
  vtkDoubleArray* radius,
  vtkDoubleArray* abscissa,
  vtkDoubleArray* tangent,
  vtkDoubleArray* normal,
  vtkDoubleArray* curvature,
  vtkDoubleArray* torsion,
  vtkIdList* line)
{
  for (std::size_t k = from; k <= to; ++k)
  {
    const vtkIdType id = points->InsertNextPoint(path.points[k].data());
    radius->InsertNextValue(path.radius[k]);
    abscissa->InsertNextValue(path.frames[k].abscissa);
    tangent->InsertNextTuple(path.frames[k].tangent.data());
    normal->InsertNextTuple(path.frames[k].normal.data());
    curvature->InsertNextValue(path.frames[k].curvature);
    torsion->InsertNextValue(path.frames[k].torsion);
    line->InsertNextId(id);
  }
}

struct PointArrays
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> radius;
  vtkNew<vtkDoubleArray> abscissa;
  vtkNew<vtkDoubleArray> tangent;
  vtkNew<vtkDoubleArray> normal;
  vtkNew<vtkDoubleArray> curvature;
  vtkNew<vtkDoubleArray> torsion;
  vtkNew<vtkCellArray> lines;

  PointArrays()
  {
    this->points->SetDataTypeToDouble();
    this->radius->SetName(VesselArrays::MaximumInscribedSphereRadius);
    this->abscissa->SetName(VesselArrays::Abscissa);
    this->tangent->SetName(VesselArrays::FrenetTangent);
    this->tangent->SetNumberOfComponents(3);
    this->normal->SetName(VesselArrays::FrenetNormal);
    this->normal->SetNumberOfComponents(3);
    this->curvature->SetName(VesselArrays::Curvature);
    this->torsion->SetName(VesselArrays::Torsion);
  }

  void Add(const PathSamples& path, std::size_t from, std::size_t to)
  {
    vtkNew<vtkIdList> line;
    AppendSamples(path,
      from,
      to,
      this->points,
      this->radius,
      this->abscissa,
      this->tangent,
      this->normal,
      this->curvature,
      this->torsion,
      line);
    this->lines->InsertNextCell(line);
  }

  vtkSmartPointer<vtkPolyData> Build()
  {
    auto out = vtkSmartPointer<vtkPolyData>::New();
    out->SetPoints(this->points);
    out->SetLines(this->lines);
    out->GetPointData()->AddArray(this->radius);
    out->GetPointData()->AddArray(this->abscissa);
    out->GetPointData()->AddArray(this->tangent);
    out->GetPointData()->AddArray(this->normal);
    out->GetPointData()->AddArray(this->curvature);
    out->GetPointData()->AddArray(this->torsion);
    return out;
  }
};

vtkSmartPointer<vtkIntArray> MakeIntArray(const char* name)
{
  auto a = vtkSmartPointer<vtkIntArray>::New();
  a->SetName(name);
  return a;
}

} // namespace

void BuildBranches(const std::vector<PathSamples>& paths,
  double medianRadius,
  double step,
  CenterlineResult& result)
{
  const std::size_t npaths = paths.size();
  // separation[i][j]: first sample index of i (and j) where they are more than one radius apart.
  std::vector<std::vector<std::size_t>> separation(npaths, std::vector<std::size_t>(npaths, 0));
  auto separate = [&](std::size_t i, std::size_t j)
  {
    const auto& a = paths[i];
    const auto& b = paths[j];
    const std::size_t window = static_cast<std::size_t>(std::ceil(4.0 * medianRadius / step)) + 2;
    for (std::size_t k = 0; k < a.points.size(); ++k)
    {
      const std::size_t lo = k > window ? k - window : 0;
      const std::size_t hi = std::min(b.points.size() - 1, k + window);
      double d = std::numeric_limits<double>::infinity();
      for (std::size_t m = lo; m <= hi && lo < b.points.size(); ++m)
      {
        d = std::min(d, Distance(a.points[k], b.points[m]));
      }
      if (d > a.radius[k])
      {
        return k;
      }
    }
    return a.points.size() - 1;
  };
  for (std::size_t i = 0; i < npaths; ++i)
  {
    for (std::size_t j = i + 1; j < npaths; ++j)
    {
      separation[i][j] = separation[j][i] = std::min(separate(i, j), separate(j, i));
    }
  }
  PointArrays branchArrays;
  auto branchId = MakeIntArray(VesselArrays::BranchId);
  auto parentId = MakeIntArray(VesselArrays::ParentBranchId);
  auto startBif = MakeIntArray(VesselArrays::StartBifurcationId);
  auto endBif = MakeIntArray(VesselArrays::EndBifurcationId);
  auto endpointId = MakeIntArray(VesselArrays::EndpointId);
  std::function<void(std::vector<std::size_t>, std::size_t, int, int)> build =
    [&](std::vector<std::size_t> group, std::size_t from, int parent, int bifurcation)
  {
    const int id = static_cast<int>(branchId->GetNumberOfTuples());
    const auto& first = paths[group[0]];
    if (group.size() == 1)
    {
      if (first.points.size() - from < 2)
      {
        result.warnings.push_back("the centerline to outlet " +
          FormatPoint(result.endpoints[first.outlet].position) +
          " ends where it leaves the others; no branch of its own");
        return;
      }
      branchArrays.Add(first, from, first.points.size() - 1);
      branchId->InsertNextValue(id);
      parentId->InsertNextValue(parent);
      startBif->InsertNextValue(bifurcation);
      endBif->InsertNextValue(-1);
      endpointId->InsertNextValue(first.outlet);
      return;
    }
    std::size_t split = std::numeric_limits<std::size_t>::max();
    for (std::size_t a = 0; a < group.size(); ++a)
    {
      for (std::size_t b = a + 1; b < group.size(); ++b)
      {
        split = std::min(split, separation[group[a]][group[b]]);
      }
    }
    split = std::max(split, from + 1);
    split = std::min(split, first.points.size() - 1);
    const int bif = static_cast<int>(result.bifurcations.size());
    Point3 centre{ { 0, 0, 0 } };
    for (std::size_t g : group)
    {
      centre = Add(centre, paths[g].points[std::min(split, paths[g].points.size() - 1)]);
    }
    result.bifurcations.push_back(Scale(centre, 1.0 / static_cast<double>(group.size())));
    branchArrays.Add(first, from, split);
    branchId->InsertNextValue(id);
    parentId->InsertNextValue(parent);
    startBif->InsertNextValue(bifurcation);
    endBif->InsertNextValue(bif);
    endpointId->InsertNextValue(-1);
    // Children: paths that stay together beyond the split go on as one group.
    UnionFind together(group.size());
    for (std::size_t a = 0; a < group.size(); ++a)
    {
      for (std::size_t b = a + 1; b < group.size(); ++b)
      {
        if (separation[group[a]][group[b]] > split)
        {
          together.Join(a, b);
        }
      }
    }
    std::vector<std::vector<std::size_t>> children;
    std::vector<std::size_t> rootOf;
    for (std::size_t a = 0; a < group.size(); ++a)
    {
      const std::size_t r = together.Find(a);
      auto it = std::find(rootOf.begin(), rootOf.end(), r);
      if (it == rootOf.end())
      {
        rootOf.push_back(r);
        children.push_back({ group[a] });
      }
      else
      {
        children[static_cast<std::size_t>(it - rootOf.begin())].push_back(group[a]);
      }
    }
    for (auto& child : children)
    {
      build(child, split, id, bif);
    }
  };
  std::vector<std::size_t> all(npaths);
  std::iota(all.begin(), all.end(), 0);
  build(all, 0, -1, -1);
  result.branches = branchArrays.Build();
  result.branches->GetCellData()->AddArray(branchId);
  result.branches->GetCellData()->AddArray(parentId);
  result.branches->GetCellData()->AddArray(startBif);
  result.branches->GetCellData()->AddArray(endBif);
  result.branches->GetCellData()->AddArray(endpointId);
  vtkNew<vtkDoubleArray> bifurcationPoints;
  bifurcationPoints->SetName(VesselArrays::BifurcationPoints);
  bifurcationPoints->SetNumberOfComponents(3);
  for (const auto& b : result.bifurcations)
  {
    bifurcationPoints->InsertNextTuple(b.data());
  }
  result.branches->GetFieldData()->AddArray(bifurcationPoints);

  PointArrays pathArrays;
  auto centerlineId = MakeIntArray(VesselArrays::CenterlineId);
  for (const auto& path : paths)
  {
    pathArrays.Add(path, 0, path.points.size() - 1);
    centerlineId->InsertNextValue(path.outlet);
  }
  result.paths = pathArrays.Build();
}

} // namespace centerline
} // namespace bender
