#include "vtkBenderWarpFilter.h"

#include "FastWarpKernel.h"
#include "GeometryErrors.h"

#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
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
#include <functional>
#include <vector>

vtkStandardNewMacro(vtkBenderWarpFilter);

// The per-grab state: which points are inside the region of influence, their projections and
// the interactive kernel's data layout (modules/Geometry).
struct vtkBenderWarpFilter::BindingCache
{
  std::unique_ptr<bender::WarpBinding> Binding;
  vtkPoints* Points = nullptr; // identity of the bound input points (not owned)
  vtkMTimeType PointsTime = 0;
  vtkIdType NumberOfPoints = 0;
  std::vector<bender::BoundPoint> Records;
  bender::FastWarpLayout Layout;
};

namespace
{
template<typename T>
struct BindWorker
{
  const bender::WarpBinding& Binding;
  const T* Xyz;
  bender::BoundPoint* Records;
  std::uint8_t* Bound;
  void operator()(vtkIdType begin, vtkIdType end)
  {
    this->Binding.BindRange(this->Xyz,
      static_cast<std::size_t>(begin),
      static_cast<std::size_t>(end),
      this->Records,
      this->Bound);
  }
};

template<typename T>
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

template<typename T>
struct CopyWorker
{
  const T* In;
  T* Out;
  void operator()(vtkIdType begin, vtkIdType end)
  {
    std::memcpy(this->Out + 3 * begin, this->In + 3 * begin, sizeof(T) * 3 * (end - begin));
  }
};

template<typename T>
struct EvaluateWorker
{
  const bender::WarpEvaluator& Evaluator;
  bender::WarpBatch<T> Batch;
  vtkSMPThreadLocal<vtkIdType> Bad;
  void operator()(vtkIdType begin, vtkIdType end)
  {
    this->Evaluator.EvaluateRange(
      this->Batch, static_cast<std::size_t>(begin), static_cast<std::size_t>(end));
    vtkIdType& bad = this->Bad.Local();
    for (vtkIdType k = begin; k < end; ++k)
    {
      const T* o = this->Batch.out + 3 * this->Batch.ids[k];
      if (!std::isfinite(o[0]) || !std::isfinite(o[1]) || !std::isfinite(o[2]))
      {
        ++bad;
      }
    }
  }
};

// The vectorised kernel for one-projection points, written into the output array.
template<typename T>
struct FastWorker
{
  const bender::FastWarpKernel& Kernel;
  const bender::FastWarpLayout& Layout;
  T* Out;
  vtkSMPThreadLocal<vtkIdType> Bad;
  void operator()(vtkIdType begin, vtkIdType end)
  {
    this->Bad.Local() += static_cast<vtkIdType>(this->Layout.EvaluateSingles(
      this->Kernel, this->Out, static_cast<std::size_t>(begin), static_cast<std::size_t>(end)));
  }
};

template<typename T>
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
template<typename F>
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
  this->Prepared.reset();
  this->Modified();
}

void vtkBenderWarpFilter::SetPreparedWarp(std::shared_ptr<const bender::RibbonWarp> warp)
{
  if (warp)
  {
    this->Spec = warp->Spec();
  }
  this->Prepared = std::move(warp);
  this->Modified();
}

void vtkBenderWarpFilter::SetInitialRibbon(const bender::RibbonSpec& ribbon)
{
  this->Spec.initial = ribbon;
  this->Prepared.reset();
  this->Modified();
}

void vtkBenderWarpFilter::SetFinalRibbon(const bender::RibbonSpec& ribbon)
{
  this->Spec.final = ribbon;
  this->Prepared.reset();
  this->Modified();
}

void vtkBenderWarpFilter::SetRadius(double r)
{
  if (this->Spec.radius != r)
  {
    this->Spec.radius = r;
    this->Prepared.reset();
    this->Modified();
  }
}

void vtkBenderWarpFilter::SetDecay(const bender::DecaySpec& decay)
{
  this->Spec.decay = decay;
  this->Prepared.reset();
  this->Modified();
}

void vtkBenderWarpFilter::SetReverseScrews(bool reverse)
{
  if (this->Spec.reverseScrews != reverse)
  {
    this->Spec.reverseScrews = reverse;
    this->Prepared.reset();
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
  return static_cast<vtkIdType>(this->Cache->Layout.BoundIds().size());
}

const std::vector<std::int64_t>& vtkBenderWarpFilter::GetBoundPointIds() const
{
  return this->Cache->Layout.BoundIds();
}

int vtkBenderWarpFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
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
  if (n == 0 || this->PassThrough)
  {
    // An empty surface is not an error: nothing to warp. Passing through shares the input's
    // points and arrays (no copy).
    output->CopyStructure(input);
    output->GetPointData()->PassData(input->GetPointData());
    output->GetCellData()->PassData(input->GetCellData());
    output->GetFieldData()->PassData(input->GetFieldData());
    return 1;
  }

  // The warp: the prepared one (validated by the caller, shared) or built and validated here
  // before touching anything (convention 11).
  std::shared_ptr<const bender::RibbonWarp> warp = this->Prepared;
  if (!warp || warp->Options().blend != this->Blend)
  {
    try
    {
      bender::WarpOptions options;
      options.blend = this->Blend;
      warp = std::make_shared<const bender::RibbonWarp>(this->Spec, options);
      ++this->WarpBuildCount;
    }
    catch (const bender::GeometryError& e)
    {
      this->LastError = std::string("invalid warp: ") + e.what();
      vtkErrorMacro(<< this->LastError);
      return 0;
    }
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
    cache.Layout.Clear();
    vtkIdType bad = 0;
    WithTypedPoints(source->GetData(),
      [&](auto xyz)
      {
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
    WithTypedPoints(source->GetData(),
      [&](auto xyz)
      {
        using T = std::remove_const_t<std::remove_pointer_t<decltype(xyz)>>;
        BindWorker<T> worker{ *cache.Binding, xyz, cache.Records.data(), bound.data() };
        vtkSMPTools::For(0, n, worker);
        cache.Layout.Build(xyz,
          static_cast<std::size_t>(n),
          cache.Records.data(),
          bound.data(),
          this->Spec.initial.start.position,
          [](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
          {
            vtkSMPTools::For(0,
              static_cast<vtkIdType>(count),
              1,
              [&body](vtkIdType first, vtkIdType last)
              { body(static_cast<std::size_t>(first), static_cast<std::size_t>(last)); });
          });
      });
    cache.Points = inPts;
    cache.PointsTime = inPts->GetMTime();
    cache.NumberOfPoints = n;
    ++this->BindingCount;
  }

  // The output points are kept from one update to the next while nobody else holds them: the
  // points outside the region of influence are then already in place and a move writes only
  // the bound points. They are (re)filled from the input after a rebind or a new allocation.
  const bool reuse = this->OutputPoints &&
    this->OutputPoints->GetDataType() == source->GetDataType() &&
    this->OutputPoints->GetNumberOfPoints() == n &&
    this->OutputPoints->GetReferenceCount() <= (output->GetPoints() == this->OutputPoints ? 2 : 1);
  if (!reuse)
  {
    this->OutputPoints = vtkSmartPointer<vtkPoints>::New();
    this->OutputPoints->SetDataType(source->GetDataType());
    this->OutputPoints->SetNumberOfPoints(n);
  }
  const bool fill = !reuse || rebind || this->FilledForBinding != this->BindingCount;
  const bender::WarpEvaluator evaluator(*warp, this->Precision);
  const bender::FastWarpLayout& layout = cache.Layout;
  vtkIdType bad = 0;
  WithTypedPoints(source->GetData(),
    [&](auto xyz)
    {
      using T = std::remove_const_t<std::remove_pointer_t<decltype(xyz)>>;
      T* out = static_cast<T*>(this->OutputPoints->GetData()->GetVoidPointer(0));
      if (fill)
      {
        CopyWorker<T> copy{ xyz, out };
        vtkSMPTools::For(0, n, copy);
        ++this->PointsCopyCount;
      }
      if (this->Precision == bender::WarpPrecision::Exact)
      {
        EvaluateWorker<T> eval{
          evaluator, { xyz, out, cache.Records.data(), layout.BoundIds().data() }, {}
        };
        vtkSMPTools::For(0, static_cast<vtkIdType>(layout.BoundIds().size()), eval);
        bad = SumLocal(eval.Bad);
        return;
      }
      bender::FastWarpKernel kernel;
      kernel.SetMotion(*evaluator.GetMotionTable(), layout.Origin());
      FastWorker<T> fast{ kernel, layout, out, {} };
      vtkSMPTools::For(0, static_cast<vtkIdType>(layout.SingleIds().size()), fast);
      EvaluateWorker<T> pairs{
        evaluator, { xyz, out, cache.Records.data(), layout.PairIds().data() }, {}
      };
      vtkSMPTools::For(0, static_cast<vtkIdType>(layout.PairIds().size()), pairs);
      bad = SumLocal(fast.Bad) + SumLocal(pairs.Bad);
    });
  this->OutputPoints->Modified();
  if (bad > 0)
  {
    // Cannot happen for a valid warp; never hand a NaN downstream if it does.
    this->FilledForBinding = -1;
    this->OutputPoints = nullptr;
    this->LastError = "the warp produced " + std::to_string(bad) + " non-finite points";
    vtkErrorMacro(<< this->LastError);
    return 0;
  }
  this->FilledForBinding = this->BindingCount;

  output->CopyStructure(input);
  output->SetPoints(this->OutputPoints);
  output->GetPointData()->PassData(input->GetPointData());
  output->GetCellData()->PassData(input->GetCellData());
  // Field data (for instance the CFD patch names and types of issue 11) describes the surface,
  // not its positions: it stays.
  output->GetFieldData()->PassData(input->GetFieldData());
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
  os << indent
     << "Decay: " << (this->Spec.decay.shape == bender::DecayShape::Bell ? "bell" : "plateau")
     << " " << this->Spec.decay.plateau << "\n";
  os << indent << "ReverseScrews: " << this->Spec.reverseScrews << "\n";
  os << indent << "BlendMode: "
     << (this->Blend == bender::BlendMode::TwoProjections ? "TwoProjections" : "SingleProjection")
     << "\n";
  os << indent
     << "Precision: " << (this->Precision == bender::WarpPrecision::Exact ? "Exact" : "Table")
     << "\n";
  os << indent << "PassThrough: " << this->PassThrough << "\n";
  os << indent << "BindingCount: " << this->BindingCount << "\n";
  os << indent << "WarpBuildCount: " << this->WarpBuildCount << "\n";
  os << indent << "PointsCopyCount: " << this->PointsCopyCount << "\n";
}
