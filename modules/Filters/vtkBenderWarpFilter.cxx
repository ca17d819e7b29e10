#include "vtkBenderWarpFilter.h"

#include "FastWarpKernel.h"
#include "GeometryErrors.h"

#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

vtkStandardNewMacro(vtkBenderWarpFilter);

// The per-grab state: which points are inside the region of influence and their projections.
struct vtkBenderWarpFilter::BindingCache
{
  std::unique_ptr<bender::WarpBinding> Binding;
  vtkPoints* Points = nullptr; // identity of the bound input points (not owned)
  vtkMTimeType PointsTime = 0;
  vtkIdType NumberOfPoints = 0;
  std::vector<bender::BoundPoint> Records;
  std::vector<std::int64_t> Ids;
  // The interactive (Table) path: points with one projection in SoA float relative to Origin,
  // evaluated by the vectorised kernel; points with two projections by the scalar evaluator.
  bender::Vec3 Origin;
  std::vector<std::int64_t> SingleIds;
  std::vector<float> Px, Py, Pz, S, F;
  std::vector<float> Ox, Oy, Oz;
  std::vector<std::int64_t> PairIds;
};

namespace
{
template <typename T>
struct BindWorker
{
  const bender::WarpBinding& Binding;
  const T* Xyz;
  bender::BoundPoint* Records;
  std::uint8_t* Bound;
  void operator()(vtkIdType begin, vtkIdType end)
  {
    this->Binding.BindRange(this->Xyz, static_cast<std::size_t>(begin),
      static_cast<std::size_t>(end), this->Records, this->Bound);
  }
};

template <typename T>
struct FiniteCheckWorker
{
  const T* Xyz;
  vtkSMPThreadLocal<vtkIdType> Bad;
  void operator()(vtkIdType begin, vtkIdType end)
  {
    vtkIdType& bad = this->Bad.Local();
    for (vtkIdType i = 3 * begin; i < 3 * end; ++i)
    {
      if (!std::isfinite(this->Xyz[i]))
      {
        ++bad;
      }
    }
  }
};

template <typename T>
struct CopyWorker
{
  const T* In;
  T* Out;
  void operator()(vtkIdType begin, vtkIdType end)
  {
    std::memcpy(this->Out + 3 * begin, this->In + 3 * begin, sizeof(T) * 3 * (end - begin));
  }
};

template <typename T>
struct EvaluateWorker
{
  const bender::WarpEvaluator& Evaluator;
  const T* In;
  T* Out;
  const bender::BoundPoint* Records;
  const std::int64_t* Ids;
  vtkSMPThreadLocal<vtkIdType> Bad;
  void operator()(vtkIdType begin, vtkIdType end)
  {
    this->Evaluator.EvaluateRange(this->In, this->Out, this->Records, this->Ids,
      static_cast<std::size_t>(begin), static_cast<std::size_t>(end));
    vtkIdType& bad = this->Bad.Local();
    for (vtkIdType k = begin; k < end; ++k)
    {
      const T* o = this->Out + 3 * this->Ids[k];
      if (!std::isfinite(o[0]) || !std::isfinite(o[1]) || !std::isfinite(o[2]))
      {
        ++bad;
      }
    }
  }
};

// The vectorised kernel for one-projection points, then a scatter into the output array.
template <typename T>
struct FastWorker
{
  const bender::FastWarpKernel& Kernel;
  const float *Px, *Py, *Pz, *S, *F;
  float *Ox, *Oy, *Oz;
  const std::int64_t* Ids;
  bender::Vec3 Origin;
  T* Out;
  vtkSMPThreadLocal<vtkIdType> Bad;
  void operator()(vtkIdType begin, vtkIdType end)
  {
    this->Kernel.Evaluate(this->Px, this->Py, this->Pz, this->S, this->F, this->Ox, this->Oy,
      this->Oz, static_cast<std::size_t>(begin), static_cast<std::size_t>(end));
    vtkIdType& bad = this->Bad.Local();
    for (vtkIdType k = begin; k < end; ++k)
    {
      T* o = this->Out + 3 * this->Ids[k];
      o[0] = static_cast<T>(this->Origin.x + this->Ox[k]);
      o[1] = static_cast<T>(this->Origin.y + this->Oy[k]);
      o[2] = static_cast<T>(this->Origin.z + this->Oz[k]);
      if (!std::isfinite(o[0]) || !std::isfinite(o[1]) || !std::isfinite(o[2]))
      {
        ++bad;
      }
    }
  }
};

template <typename T>
vtkIdType SumLocal(vtkSMPThreadLocal<T>& local)
{
  vtkIdType sum = 0;
  for (auto it = local.begin(); it != local.end(); ++it)
  {
    sum += *it;
  }
  return sum;
}

// Runs f(const T* in) on the typed pointer of float or double points.
template <typename F>
bool WithTypedPoints(vtkDataArray* data, F&& f)
{
  if (auto* fa = vtkFloatArray::FastDownCast(data))
  {
    f(static_cast<const float*>(fa->GetPointer(0)));
    return true;
  }
  if (auto* da = vtkDoubleArray::FastDownCast(data))
  {
    f(static_cast<const double*>(da->GetPointer(0)));
    return true;
  }
  return false;
}
} // namespace

vtkBenderWarpFilter::vtkBenderWarpFilter()
  : Cache(new BindingCache)
{
  this->Spec.initial.start.position = { 0, 0, 0 };
  this->Spec.initial.end.position = { 1, 0, 0 };
  this->Spec.final = this->Spec.initial;
  this->Spec.radius = 1.0;
}

vtkBenderWarpFilter::~vtkBenderWarpFilter() = default;

void vtkBenderWarpFilter::SetWarp(const bender::WarpSpec& spec)
{
  this->Spec = spec;
  this->Modified();
}

void vtkBenderWarpFilter::SetInitialRibbon(const bender::RibbonSpec& ribbon)
{
  this->Spec.initial = ribbon;
  this->Modified();
}

void vtkBenderWarpFilter::SetFinalRibbon(const bender::RibbonSpec& ribbon)
{
  this->Spec.final = ribbon;
  this->Modified();
}

void vtkBenderWarpFilter::SetRadius(double r)
{
  if (this->Spec.radius != r)
  {
    this->Spec.radius = r;
    this->Modified();
  }
}

void vtkBenderWarpFilter::SetDecay(const bender::DecaySpec& decay)
{
  this->Spec.decay = decay;
  this->Modified();
}

void vtkBenderWarpFilter::SetReverseScrews(bool reverse)
{
  if (this->Spec.reverseScrews != reverse)
  {
    this->Spec.reverseScrews = reverse;
    this->Modified();
  }
}

void vtkBenderWarpFilter::SetBlendMode(bender::BlendMode mode)
{
  if (this->Blend != mode)
  {
    this->Blend = mode;
    this->Modified();
  }
}

void vtkBenderWarpFilter::SetPrecision(bender::WarpPrecision precision)
{
  if (this->Precision != precision)
  {
    this->Precision = precision;
    this->Modified();
  }
}

vtkIdType vtkBenderWarpFilter::GetNumberOfBoundPoints() const
{
  return static_cast<vtkIdType>(this->Cache->Ids.size());
}

int vtkBenderWarpFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->LastError.clear();
  this->LastWarning.clear();
  if (!input || !output)
  {
    this->LastError = "no input surface";
    vtkErrorMacro(<< this->LastError);
    return 0;
  }
  vtkPoints* inPts = input->GetPoints();
  const vtkIdType n = inPts ? inPts->GetNumberOfPoints() : 0;
  if (n == 0)
  {
    // An empty surface is not an error: nothing to warp.
    output->CopyStructure(input);
    output->GetPointData()->PassData(input->GetPointData());
    output->GetCellData()->PassData(input->GetCellData());
    return 1;
  }

  // Validate the whole warp before touching anything (convention 11).
  std::unique_ptr<bender::RibbonWarp> warp;
  try
  {
    bender::WarpOptions options;
    options.blend = this->Blend;
    warp.reset(new bender::RibbonWarp(this->Spec, options));
  }
  catch (const bender::InvalidRibbonError& e)
  {
    this->LastError = std::string("invalid warp: ") + e.what();
    vtkErrorMacro(<< this->LastError);
    return 0;
  }

  // Work in float or double as the input does; other point types are converted to double.
  vtkSmartPointer<vtkPoints> source = inPts;
  if (inPts->GetDataType() != VTK_FLOAT && inPts->GetDataType() != VTK_DOUBLE)
  {
    source = vtkSmartPointer<vtkPoints>::New();
    source->SetDataTypeToDouble();
    source->DeepCopy(inPts);
  }

  // (Re)bind when the points or the initial ribbon / radius / decay / blend changed.
  BindingCache& cache = *this->Cache;
  const bool rebind = !cache.Binding || cache.Points != inPts ||
    cache.PointsTime != inPts->GetMTime() || cache.NumberOfPoints != n ||
    !cache.Binding->Matches(this->Spec, this->Blend);
  if (rebind)
  {
    cache.Binding.reset();
    cache.Ids.clear();
    vtkIdType bad = 0;
    WithTypedPoints(source->GetData(), [&](auto xyz) {
      using T = std::remove_const_t<std::remove_pointer_t<decltype(xyz)>>;
      FiniteCheckWorker<T> check{ xyz, {} };
      vtkSMPTools::For(0, n, check);
      bad = SumLocal(check.Bad);
    });
    if (bad > 0)
    {
      this->LastError = "the input surface has " + std::to_string(bad) +
        " non-finite (NaN or infinite) point coordinates";
      vtkErrorMacro(<< this->LastError);
      return 0;
    }
    cache.Binding.reset(new bender::WarpBinding(this->Spec, this->Blend));
    cache.Records.resize(static_cast<std::size_t>(n));
    std::vector<std::uint8_t> bound(static_cast<std::size_t>(n));
    WithTypedPoints(source->GetData(), [&](auto xyz) {
      using T = std::remove_const_t<std::remove_pointer_t<decltype(xyz)>>;
      BindWorker<T> worker{ *cache.Binding, xyz, cache.Records.data(), bound.data() };
      vtkSMPTools::For(0, n, worker);
    });
    cache.SingleIds.clear();
    cache.PairIds.clear();
    cache.Px.clear();
    cache.Py.clear();
    cache.Pz.clear();
    cache.S.clear();
    cache.F.clear();
    cache.Origin = this->Spec.initial.start.position;
    vtkDataArray* dataArray = source->GetData();
    const std::size_t expected = static_cast<std::size_t>(
      std::count(bound.begin(), bound.end(), std::uint8_t(1)));
    cache.Ids.reserve(expected);
    cache.SingleIds.reserve(expected);
    for (auto* v : { &cache.Px, &cache.Py, &cache.Pz, &cache.S, &cache.F })
    {
      v->reserve(expected);
    }
    for (vtkIdType i = 0; i < n; ++i)
    {
      if (!bound[i])
      {
        continue;
      }
      cache.Ids.push_back(i);
      const bender::BoundPoint& rec = cache.Records[i];
      if (rec.lambda0 < 1.0)
      {
        cache.PairIds.push_back(i);
        continue;
      }
      double p[3];
      dataArray->GetTuple(i, p);
      cache.SingleIds.push_back(i);
      cache.Px.push_back(static_cast<float>(p[0] - cache.Origin.x));
      cache.Py.push_back(static_cast<float>(p[1] - cache.Origin.y));
      cache.Pz.push_back(static_cast<float>(p[2] - cache.Origin.z));
      cache.S.push_back(static_cast<float>(rec.s0));
      cache.F.push_back(static_cast<float>(rec.f));
    }
    cache.Ox.resize(cache.SingleIds.size());
    cache.Oy.resize(cache.SingleIds.size());
    cache.Oz.resize(cache.SingleIds.size());
    cache.Points = inPts;
    cache.PointsTime = inPts->GetMTime();
    cache.NumberOfPoints = n;
    ++this->BindingCount;
  }

  vtkNew<vtkPoints> outPts;
  outPts->SetDataType(source->GetDataType());
  outPts->SetNumberOfPoints(n);
  const bender::WarpEvaluator evaluator(*warp, this->Precision);
  vtkIdType bad = 0;
  WithTypedPoints(source->GetData(), [&](auto xyz) {
    using T = std::remove_const_t<std::remove_pointer_t<decltype(xyz)>>;
    T* out = static_cast<T*>(outPts->GetData()->GetVoidPointer(0));
    CopyWorker<T> copy{ xyz, out };
    vtkSMPTools::For(0, n, copy);
    if (this->Precision == bender::WarpPrecision::Exact)
    {
      EvaluateWorker<T> eval{ evaluator, xyz, out, cache.Records.data(), cache.Ids.data(), {} };
      vtkSMPTools::For(0, static_cast<vtkIdType>(cache.Ids.size()), eval);
      bad = SumLocal(eval.Bad);
      return;
    }
    bender::FastWarpKernel kernel;
    kernel.SetMotion(*evaluator.GetMotionTable(), cache.Origin);
    FastWorker<T> fast{ kernel, cache.Px.data(), cache.Py.data(), cache.Pz.data(),
      cache.S.data(), cache.F.data(), cache.Ox.data(), cache.Oy.data(), cache.Oz.data(),
      cache.SingleIds.data(), cache.Origin, out, {} };
    vtkSMPTools::For(0, static_cast<vtkIdType>(cache.SingleIds.size()), fast);
    EvaluateWorker<T> pairs{ evaluator, xyz, out, cache.Records.data(), cache.PairIds.data(),
      {} };
    vtkSMPTools::For(0, static_cast<vtkIdType>(cache.PairIds.size()), pairs);
    bad = SumLocal(fast.Bad) + SumLocal(pairs.Bad);
  });
  if (bad > 0)
  {
    // Cannot happen for a valid warp; never hand a NaN downstream if it does.
    this->LastError = "the warp produced " + std::to_string(bad) + " non-finite points";
    vtkErrorMacro(<< this->LastError);
    return 0;
  }

  output->CopyStructure(input);
  output->SetPoints(outPts);
  output->GetPointData()->PassData(input->GetPointData());
  output->GetCellData()->PassData(input->GetCellData());
  // Normals are stale after a warp: remove them (recompute downstream).
  output->GetPointData()->SetNormals(nullptr);
  output->GetCellData()->SetNormals(nullptr);

  this->SpaceInversionRisk = warp->SpaceInversionRisk();
  this->LastWarning = warp->SpaceInversionWarning();
  this->FlipOccurred = warp->FlipOccurred();
  this->InitialMinimumRadius = warp->InitialMinimumRadius();
  return 1;
}

void vtkBenderWarpFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Radius: " << this->Spec.radius << "\n";
  os << indent << "Decay: "
     << (this->Spec.decay.shape == bender::DecayShape::Bell ? "bell" : "plateau") << " "
     << this->Spec.decay.plateau << "\n";
  os << indent << "ReverseScrews: " << this->Spec.reverseScrews << "\n";
  os << indent << "BlendMode: "
     << (this->Blend == bender::BlendMode::TwoProjections ? "TwoProjections" : "SingleProjection")
     << "\n";
  os << indent << "Precision: "
     << (this->Precision == bender::WarpPrecision::Exact ? "Exact" : "Table") << "\n";
  os << indent << "BindingCount: " << this->BindingCount << "\n";
}
