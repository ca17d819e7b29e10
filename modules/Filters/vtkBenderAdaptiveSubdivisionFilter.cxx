#include "vtkBenderAdaptiveSubdivisionFilter.h"

#include "GeometryErrors.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <sstream>
#include <unordered_map>

vtkStandardNewMacro(vtkBenderAdaptiveSubdivisionFilter);

namespace
{
// About 50 million triangles: a few GB of memory for the subdivided surface and its data.
constexpr vtkIdType MaximumPoints = 25000000;

using Triangle = std::array<vtkIdType, 3>;

// Undirected edge key (min, max); meshes stay below 2^32 points.
inline std::uint64_t EdgeKey(vtkIdType a, vtkIdType b)
{
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}
inline vtkIdType KeyLow(std::uint64_t k)
{
  return static_cast<vtkIdType>(k >> 32);
}
inline vtkIdType KeyHigh(std::uint64_t k)
{
  return static_cast<vtkIdType>(k & 0xffffffffu);
}

inline bender::Vec3 At(const std::vector<double>& xyz, vtkIdType i)
{
  return { xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] };
}

// W(p): the exact warp, identity outside the region of influence.
struct WarpAt
{
  const bender::WarpBinding& Binding;
  const bender::WarpEvaluator& Evaluator;
  bender::Vec3 operator()(const bender::Vec3& p) const
  {
    bender::BoundPoint rec;
    return this->Binding.Bind(p, rec) ? this->Evaluator.Apply(p, rec) : p;
  }
};

// Y[i] = W(X[i]) for the original vertices.
struct WarpVerticesWorker
{
  const WarpAt& W;
  const std::vector<double>& X;
  std::vector<double>& Y;
  void operator()(vtkIdType begin, vtkIdType end)
  {
    for (vtkIdType i = begin; i < end; ++i)
    {
      const bender::Vec3 y = this->W(At(this->X, i));
      this->Y[3 * i] = y.x;
      this->Y[3 * i + 1] = y.y;
      this->Y[3 * i + 2] = y.z;
    }
  }
};

// The edge test of spec 7 over the work list; caches the midpoint and its warp.
struct EdgeTestWorker
{
  const WarpAt& W;
  const std::vector<double>& X;
  const std::vector<double>& Y;
  const std::vector<std::uint64_t>& Work;
  double Tolerance;
  std::vector<double>& MidX;
  std::vector<double>& MidY;
  std::vector<std::uint8_t>& Marked;
  vtkSMPThreadLocal<double> MaxDeviation;
  void operator()(vtkIdType begin, vtkIdType end)
  {
    double& maxDev = this->MaxDeviation.Local();
    for (vtkIdType k = begin; k < end; ++k)
    {
      const vtkIdType a = KeyLow(this->Work[k]);
      const vtkIdType b = KeyHigh(this->Work[k]);
      const bender::Vec3 m = (At(this->X, a) + At(this->X, b)) * 0.5;
      const bender::Vec3 wm = this->W(m);
      const bender::Vec3 d = wm - (At(this->Y, a) + At(this->Y, b)) * 0.5;
      const double dev = std::sqrt(bender::Dot(d, d));
      // A non-finite deviation is marked too, so that the caller sees the bad point.
      const bool mark = !(dev <= this->Tolerance);
      this->Marked[k] = mark ? 1 : 0;
      maxDev = std::max(maxDev, std::isfinite(dev) ? dev : HUGE_VAL);
      if (mark)
      {
        for (int c = 0; c < 3; ++c)
        {
          this->MidX[3 * k + c] = m[c];
          this->MidY[3 * k + c] = wm[c];
        }
      }
    }
  }
};

double Distance(const std::vector<double>& y, vtkIdType a, vtkIdType b)
{
  const bender::Vec3 d = At(y, a) - At(y, b);
  return std::sqrt(bender::Dot(d, d));
}
} // namespace

vtkBenderAdaptiveSubdivisionFilter::vtkBenderAdaptiveSubdivisionFilter()
{
  this->Spec.initial.start.position = { 0, 0, 0 };
  this->Spec.initial.end.position = { 1, 0, 0 };
  this->Spec.final = this->Spec.initial;
  this->Spec.radius = 1.0;
}

vtkBenderAdaptiveSubdivisionFilter::~vtkBenderAdaptiveSubdivisionFilter() = default;

void vtkBenderAdaptiveSubdivisionFilter::SetWarp(const bender::WarpSpec& spec)
{
  this->Spec = spec;
  if (spec.subdivision)
  {
    this->Tolerance = spec.subdivision->tolerance;
    this->MaxPasses = std::clamp(spec.subdivision->maxPasses, 0, 64);
  }
  this->Modified();
}

void vtkBenderAdaptiveSubdivisionFilter::SetBlendMode(bender::BlendMode mode)
{
  if (this->Blend != mode)
  {
    this->Blend = mode;
    this->Modified();
  }
}

void vtkBenderAdaptiveSubdivisionFilter::SetPrecision(bender::WarpPrecision precision)
{
  if (this->Precision != precision)
  {
    this->Precision = precision;
    this->Modified();
  }
}

int vtkBenderAdaptiveSubdivisionFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->LastError.clear();
  this->SplitsPerPass.clear();
  this->Converged = false;
  this->LastMaximumDeviation = 0.0;
  auto fail = [this](const std::string& message)
  {
    this->LastError = message;
    vtkErrorMacro(<< message);
    return 0;
  };
  if (!input || !output)
  {
    return fail("no input surface");
  }
  if (!(this->Tolerance > 0.0) || !std::isfinite(this->Tolerance))
  {
    return fail("the subdivision tolerance must be a finite number > 0, not " +
      std::to_string(this->Tolerance));
  }
  const vtkIdType n0 = input->GetNumberOfPoints();
  if (n0 == 0)
  {
    this->Converged = true;
    return 1;
  }
  if (n0 >= (vtkIdType(1) << 31))
  {
    return fail("the input surface has too many points (2^31 or more)");
  }
  {
    // Bounded up front: a tolerance below the rounding noise of the surface's coordinates
    // never converges, so every pass may split every edge where W bends (4x the triangles).
    // Refuse when that worst case over MaxPasses passes would pass the point limit, before
    // any work (1e-12 with 64 passes took minutes and gigabytes before the limit stopped it).
    double bounds[6];
    input->GetBounds(bounds);
    const double size = std::max({ bounds[1] - bounds[0],
      bounds[3] - bounds[2],
      bounds[5] - bounds[4],
      std::fabs(bounds[0]),
      std::fabs(bounds[1]),
      std::fabs(bounds[2]),
      std::fabs(bounds[3]),
      std::fabs(bounds[4]),
      std::fabs(bounds[5]) });
    const double noise = std::max(size, 1e-300) * 1e-9;
    const double worstPoints =
      static_cast<double>(n0) * std::pow(4.0, static_cast<double>(this->MaxPasses));
    if (this->Tolerance < noise && worstPoints > static_cast<double>(MaximumPoints))
    {
      std::ostringstream message;
      message << "subdivision tolerance " << this->Tolerance << " is below the rounding noise ("
              << noise << ") of a surface " << size << " across: with " << this->MaxPasses
              << " passes on " << n0 << " points it could grow past " << MaximumPoints
              << " points; use a larger tolerance or fewer passes";
      return fail(message.str());
    }
  }

  std::unique_ptr<bender::RibbonWarp> warp;
  std::unique_ptr<bender::WarpBinding> binding;
  try
  {
    bender::WarpOptions options;
    options.blend = this->Blend;
    warp.reset(new bender::RibbonWarp(this->Spec, options));
    binding.reset(new bender::WarpBinding(this->Spec, this->Blend));
  }
  catch (const bender::GeometryError& e) // an invalid ribbon or warp
  {
    return fail(std::string("invalid warp: ") + e.what());
  }
  const bender::WarpEvaluator evaluator(*warp, this->Precision);
  const WarpAt w{ *binding, evaluator };

  // Pre-warp positions X of every vertex, old and new.
  std::vector<double> x(static_cast<std::size_t>(3 * n0));
  for (vtkIdType i = 0; i < n0; ++i)
  {
    input->GetPoint(i, &x[3 * i]);
  }
  const auto badX = std::count_if(x.begin(), x.end(), [](double v) { return !std::isfinite(v); });
  if (badX > 0)
  {
    return fail("the input surface has " + std::to_string(badX) +
      " non-finite (NaN or infinite) point coordinates");
  }

  // Triangles (polygons fanned, strips converted) and the input cell each comes from.
  std::vector<Triangle> tris;
  std::vector<vtkIdType> triCell;
  {
    vtkIdType cellId = input->GetNumberOfVerts() + input->GetNumberOfLines();
    auto it = vtk::TakeSmartPointer(input->GetPolys()->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cellId)
    {
      vtkIdType npts;
      const vtkIdType* pts;
      it->GetCurrentCell(npts, pts);
      for (vtkIdType k = 1; k + 1 < npts; ++k)
      {
        tris.push_back({ pts[0], pts[k], pts[k + 1] });
        triCell.push_back(cellId);
      }
    }
    auto st = vtk::TakeSmartPointer(input->GetStrips()->NewIterator());
    for (st->GoToFirstCell(); !st->IsDoneWithTraversal(); st->GoToNextCell(), ++cellId)
    {
      vtkIdType npts;
      const vtkIdType* pts;
      st->GetCurrentCell(npts, pts);
      for (vtkIdType k = 0; k + 2 < npts; ++k)
      {
        if (k % 2 == 0)
        {
          tris.push_back({ pts[k], pts[k + 1], pts[k + 2] });
        }
        else
        {
          tris.push_back({ pts[k + 1], pts[k], pts[k + 2] });
        }
        triCell.push_back(cellId);
      }
    }
  }

  // Warped positions Y = W(X) of the original vertices.
  std::vector<double> y(x.size());
  WarpVerticesWorker warpVertices{ w, x, y };
  vtkSMPTools::For(0, n0, warpVertices);
  if (std::any_of(y.begin(), y.end(), [](double v) { return !std::isfinite(v); }))
  {
    return fail("the warp produced non-finite points");
  }

  // Work list: every (non-degenerate) edge of the initial mesh.
  std::vector<std::uint64_t> work;
  work.reserve(3 * tris.size());
  for (const Triangle& t : tris)
  {
    for (int e = 0; e < 3; ++e)
    {
      if (t[e] != t[(e + 1) % 3])
      {
        work.push_back(EdgeKey(t[e], t[(e + 1) % 3]));
      }
    }
  }
  auto sortUnique = [](std::vector<std::uint64_t>& v)
  {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  };
  sortUnique(work);

  // Parents (a, b) of every new vertex, in creation order, for point data interpolation.
  std::vector<std::pair<vtkIdType, vtkIdType>> parents;
  std::unordered_map<std::uint64_t, vtkIdType> midpoint;
  std::vector<double> midX, midY;
  std::vector<std::uint8_t> marked;
  for (int pass = 0; pass < this->MaxPasses && !work.empty(); ++pass)
  {
    const auto nWork = static_cast<vtkIdType>(work.size());
    midX.assign(3 * work.size(), 0.0);
    midY.assign(3 * work.size(), 0.0);
    marked.assign(work.size(), 0);
    EdgeTestWorker test{ w, x, y, work, this->Tolerance, midX, midY, marked, {} };
    vtkSMPTools::For(0, nWork, test);
    double maxDev = 0.0;
    for (auto it = test.MaxDeviation.begin(); it != test.MaxDeviation.end(); ++it)
    {
      maxDev = std::max(maxDev, *it);
    }
    this->LastMaximumDeviation = maxDev;

    // Create the midpoint vertices (sequential: deterministic numbering).
    midpoint.clear();
    std::vector<std::uint64_t> next;
    for (vtkIdType k = 0; k < nWork; ++k)
    {
      if (!marked[k])
      {
        continue;
      }
      for (int c = 0; c < 3; ++c)
      {
        if (!std::isfinite(midY[3 * k + c]))
        {
          return fail("the warp produced non-finite points");
        }
      }
      const vtkIdType id = static_cast<vtkIdType>(x.size() / 3);
      // Each split vertex adds about two triangles: stop long before memory runs out.
      if (id >= MaximumPoints)
      {
        return fail("subdivision would exceed " + std::to_string(MaximumPoints) +
          " points (the tolerance is too small for this warp); raise the tolerance");
      }
      x.insert(x.end(), &midX[3 * k], &midX[3 * k] + 3);
      y.insert(y.end(), &midY[3 * k], &midY[3 * k] + 3);
      const vtkIdType a = KeyLow(work[k]);
      const vtkIdType b = KeyHigh(work[k]);
      parents.emplace_back(a, b);
      midpoint.emplace(work[k], id);
      next.push_back(EdgeKey(a, id));
      next.push_back(EdgeKey(id, b));
    }
    if (midpoint.empty())
    {
      this->Converged = true;
      break;
    }
    this->SplitsPerPass.push_back(static_cast<vtkIdType>(midpoint.size()));

    // Split every triangle with marked edges into m + 1 triangles (spec 7 patterns).
    std::vector<Triangle> outTris;
    std::vector<vtkIdType> outCell;
    outTris.reserve(tris.size() + 3 * midpoint.size());
    outCell.reserve(outTris.capacity());
    auto emit = [&](vtkIdType a, vtkIdType b, vtkIdType c, vtkIdType cell)
    {
      outTris.push_back({ a, b, c });
      outCell.push_back(cell);
    };
    for (std::size_t t = 0; t < tris.size(); ++t)
    {
      const Triangle& tri = tris[t];
      std::array<vtkIdType, 3> mid{ -1, -1, -1 }; // mid[e]: midpoint of edge (e, e+1)
      int m = 0;
      for (int e = 0; e < 3; ++e)
      {
        const vtkIdType a = tri[e];
        const vtkIdType b = tri[(e + 1) % 3];
        if (a == b)
        {
          continue;
        }
        const auto found = midpoint.find(EdgeKey(a, b));
        if (found != midpoint.end())
        {
          mid[e] = found->second;
          ++m;
        }
      }
      const vtkIdType cell = triCell[t];
      if (m == 0)
      {
        emit(tri[0], tri[1], tri[2], cell);
        continue;
      }
      if (m == 3)
      {
        const vtkIdType m01 = mid[0], m12 = mid[1], m20 = mid[2];
        emit(tri[0], m01, m20, cell);
        emit(m01, tri[1], m12, cell);
        emit(m20, m12, tri[2], cell);
        emit(m01, m12, m20, cell);
        next.push_back(EdgeKey(m01, m12));
        next.push_back(EdgeKey(m12, m20));
        next.push_back(EdgeKey(m20, m01));
        continue;
      }
      // Rotate labels: for m = 1 the marked edge becomes (v0, v1); for m = 2 the unmarked
      // edge becomes (v2, v0). Orientation is kept.
      int r = 0;
      if (m == 1)
      {
        r = mid[0] >= 0 ? 0 : (mid[1] >= 0 ? 1 : 2);
      }
      else
      {
        r = mid[2] < 0 ? 0 : (mid[0] < 0 ? 1 : 2);
      }
      const vtkIdType v0 = tri[r], v1 = tri[(r + 1) % 3], v2 = tri[(r + 2) % 3];
      const vtkIdType m01 = mid[r];
      if (m == 1)
      {
        emit(v0, m01, v2, cell);
        emit(m01, v1, v2, cell);
        next.push_back(EdgeKey(m01, v2));
        continue;
      }
      const vtkIdType m12 = mid[(r + 1) % 3];
      emit(m01, v1, m12, cell);
      // The quad (v0, m01, m12, v2): shorter diagonal in warped positions; near-ties go to
      // the diagonal with the smaller vertex index.
      const double d1 = Distance(y, m01, v2);
      const double d2 = Distance(y, m12, v0);
      bool useFirst;
      if (std::abs(d1 - d2) <= 1e-9 * std::max(d1, d2))
      {
        useFirst = std::min(m01, v2) <= std::min(m12, v0);
      }
      else
      {
        useFirst = d1 < d2;
      }
      if (useFirst)
      {
        emit(v0, m01, v2, cell);
        emit(m01, m12, v2, cell);
        next.push_back(EdgeKey(m01, v2));
      }
      else
      {
        emit(v0, m01, m12, cell);
        emit(v0, m12, v2, cell);
        next.push_back(EdgeKey(v0, m12));
      }
      next.push_back(EdgeKey(m01, m12));
    }
    tris.swap(outTris);
    triCell.swap(outCell);
    sortUnique(next);
    work.swap(next);
  }
  if (work.empty())
  {
    this->Converged = true;
  }

  // Output: warped points, triangles, interpolated point data, copied cell data.
  const vtkIdType n = static_cast<vtkIdType>(y.size() / 3);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  std::copy(y.begin(), y.end(), static_cast<double*>(points->GetData()->GetVoidPointer(0)));
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(
    static_cast<vtkIdType>(tris.size()), 3 * static_cast<vtkIdType>(tris.size()));
  for (const Triangle& t : tris)
  {
    polys->InsertNextCell(3, t.data());
  }
  output->Initialize();
  output->SetPoints(points);
  output->SetPolys(polys);

  vtkPointData* inPD = input->GetPointData();
  vtkPointData* outPD = output->GetPointData();
  outPD->CopyNormalsOff();
  outPD->CopyAllocate(inPD, n);
  for (vtkIdType i = 0; i < n0; ++i)
  {
    outPD->CopyData(inPD, i, i);
  }
  for (int a = 0; a < outPD->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = outPD->GetAbstractArray(a);
    array->SetNumberOfTuples(n);
    for (std::size_t k = 0; k < parents.size(); ++k)
    {
      array->InterpolateTuple(
        n0 + static_cast<vtkIdType>(k), parents[k].first, array, parents[k].second, array, 0.5);
    }
  }
  if (this->KeepInitialPositions)
  {
    vtkNew<vtkDoubleArray> initial;
    initial->SetName(InitialPositionArrayName());
    initial->SetNumberOfComponents(3);
    initial->SetNumberOfTuples(n);
    std::copy(x.begin(), x.end(), initial->GetPointer(0));
    outPD->AddArray(initial);
  }

  vtkCellData* inCD = input->GetCellData();
  vtkCellData* outCD = output->GetCellData();
  outCD->CopyNormalsOff();
  outCD->CopyAllocate(inCD, static_cast<vtkIdType>(tris.size()));
  // Each child triangle inherits its parent's cell data (the CFD patch labels among them);
  // the field data (the patch names and types) is passed on as is.
  for (std::size_t t = 0; t < tris.size(); ++t)
  {
    outCD->CopyData(inCD, triCell[t], static_cast<vtkIdType>(t));
  }
  // (vtkFieldData::PassData skips string arrays: add every array.)
  vtkFieldData* inFD = input->GetFieldData();
  for (int a = 0; inFD && a < inFD->GetNumberOfArrays(); ++a)
  {
    output->GetFieldData()->AddArray(inFD->GetAbstractArray(a));
  }
  return 1;
}

void vtkBenderAdaptiveSubdivisionFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "MaxPasses: " << this->MaxPasses << "\n";
  os << indent << "Radius: " << this->Spec.radius << "\n";
  os << indent << "KeepInitialPositions: " << this->KeepInitialPositions << "\n";
  os << indent
     << "Precision: " << (this->Precision == bender::WarpPrecision::Exact ? "Exact" : "Table")
     << "\n";
}
