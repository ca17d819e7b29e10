#include "vtkBenderCapFilter.h"

#include "MeshTopology.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkIdList.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

vtkStandardNewMacro(vtkBenderCapFilter);

int vtkBenderCapFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->LastError.clear();
  this->NumberOfCaps = 0;
  this->NumberOfSkippedLoops = 0;
  if (!input || !output)
  {
    this->LastError = "no input surface";
    vtkErrorMacro(<< this->LastError);
    return 0;
  }
  const vtkIdType n0 = input->GetNumberOfPoints();
  std::vector<std::array<double, 3>> x(static_cast<std::size_t>(n0));
  for (vtkIdType i = 0; i < n0; ++i)
  {
    input->GetPoint(i, x[i].data());
    if (!std::isfinite(x[i][0]) || !std::isfinite(x[i][1]) || !std::isfinite(x[i][2]))
    {
      this->LastError = "the input surface has non-finite (NaN or infinite) point coordinates";
      vtkErrorMacro(<< this->LastError);
      return 0;
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
  std::vector<std::vector<vtkIdType>> loops;
  int broken = 0;
  for (const bender::BoundaryChain& chain : bender::BoundaryLoops(tris, n0))
  {
    if (chain.closed && chain.vertices.size() >= 3)
    {
      loops.emplace_back(chain.vertices.begin(), chain.vertices.end());
    }
    else
    {
      ++broken;
    }
  }
  this->NumberOfSkippedLoops = broken;
  std::sort(loops.begin(),
    loops.end(),
    [](const auto& a, const auto& b)
    {
      return a.size() != b.size()
        ? a.size() > b.size()
        : *std::min_element(a.begin(), a.end()) < *std::min_element(b.begin(), b.end());
    });

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const auto& p : x)
  {
    points->InsertNextPoint(p.data());
  }
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIntArray> patch;
  patch->SetName(PatchIdArrayName());
  for (std::size_t t = 0; t < tris.size(); t += 3)
  {
    const vtkIdType ids[3] = { tris[t], tris[t + 1], tris[t + 2] };
    polys->InsertNextCell(3, ids);
    patch->InsertNextValue(0);
  }
  const vtkIdType wallTriangles = polys->GetNumberOfCells();

  vtkPointData* outPD = output->GetPointData();
  vtkPointData* inPD = input->GetPointData();
  vtkNew<vtkPointData> pd;
  pd->CopyNormalsOff();
  pd->InterpolateAllocate(inPD, n0 + static_cast<vtkIdType>(loops.size()));
  for (vtkIdType i = 0; i < n0; ++i)
  {
    pd->CopyData(inPD, i, i);
  }
  for (const auto& loop : loops)
  {
    // Least-squares plane: centroid and the smallest eigenvector of the covariance.
    double c[3] = { 0, 0, 0 };
    for (vtkIdType v : loop)
    {
      for (int a = 0; a < 3; ++a)
      {
        c[a] += x[v][a] / static_cast<double>(loop.size());
      }
    }
    double cov[3][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } };
    double diameter = 0.0;
    for (vtkIdType v : loop)
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
    const double normal[3] = { vecs[0][2], vecs[1][2], vecs[2][2] };
    double worst = 0.0;
    for (vtkIdType v : loop)
    {
      const double d[3] = { x[v][0] - c[0], x[v][1] - c[1], x[v][2] - c[2] };
      worst = std::max(worst, std::abs(vtkMath::Dot(d, normal)));
    }
    if (worst > this->Planarity * diameter)
    {
      ++this->NumberOfSkippedLoops;
      continue;
    }
    const vtkIdType centre = points->InsertNextPoint(c);
    vtkNew<vtkIdList> ids;
    std::vector<double> weights(loop.size(), 1.0 / static_cast<double>(loop.size()));
    for (vtkIdType v : loop)
    {
      ids->InsertNextId(v);
    }
    pd->InterpolatePoint(inPD, centre, ids, weights.data());
    ++this->NumberOfCaps;
    for (std::size_t k = 0; k < loop.size(); ++k)
    {
      // The wall traverses a -> b; the cap traverses b -> a.
      const vtkIdType a = loop[k], b = loop[(k + 1) % loop.size()];
      const vtkIdType cap[3] = { b, a, centre };
      polys->InsertNextCell(3, cap);
      patch->InsertNextValue(this->NumberOfCaps);
    }
  }

  output->Initialize();
  output->SetPoints(points);
  output->SetPolys(polys);
  outPD->ShallowCopy(pd);
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
  outCD->RemoveArray(PatchIdArrayName());
  outCD->AddArray(patch);
  return 1;
}

void vtkBenderCapFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Planarity: " << this->Planarity << "\n";
  os << indent << "NumberOfCaps: " << this->NumberOfCaps << "\n";
}
