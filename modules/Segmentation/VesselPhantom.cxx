#include "VesselPhantom.h"

#include "ItkVtkBridge.h"

#include <vtkCellArray.h>
#include <vtkCleanPolyData.h>
#include <vtkFeatureEdges.h>
#include <vtkFillHolesFilter.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkImageGaussianSmooth.h>
#include <vtkImageStencilData.h>
#include <vtkImageStencilToImage.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataToImageStencil.h>
#include <vtkStripper.h>
#include <vtkTriangleFilter.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace bender
{
namespace
{

void Require(bool ok, const char* message)
{
  if (!ok)
  {
    throw ParameterError(std::string("phantom parameter ") + message);
  }
}

vtkSmartPointer<vtkImageData> FloatImage(const ImageGeometry& g, const std::vector<float>& values)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(int(g.size[0]), int(g.size[1]), int(g.size[2]));
  image->SetSpacing(g.spacing.data());
  image->SetOrigin(g.origin.data());
  vtkNew<vtkFloatArray> scalars;
  scalars->SetNumberOfValues(vtkIdType(values.size()));
  std::copy(values.begin(), values.end(), scalars->GetPointer(0));
  image->GetPointData()->SetScalars(scalars);
  return image;
}

std::vector<float> Blur(const ImageGeometry& g, const std::vector<float>& values, double sigmaMm)
{
  if (sigmaMm <= 0.0)
  {
    return values;
  }
  vtkNew<vtkImageGaussianSmooth> gauss;
  gauss->SetInputData(FloatImage(g, values));
  gauss->SetDimensionality(3);
  gauss->SetStandardDeviations(
    sigmaMm / g.spacing[0], sigmaMm / g.spacing[1], sigmaMm / g.spacing[2]);
  gauss->SetRadiusFactors(3.0, 3.0, 3.0);
  gauss->Update();
  const float* out =
    static_cast<const float*>(gauss->GetOutput()->GetPointData()->GetScalars()->GetVoidPointer(0));
  return std::vector<float>(out, out + values.size());
}

double Sample(const ImageGeometry& g, const std::vector<float>& values, const Point3& p)
{
  const Point3 ci = g.PhysicalToIndex(p);
  long idx[3];
  for (int c = 0; c < 3; ++c)
  {
    idx[c] = std::lround(ci[c]);
    if (idx[c] < 0 || idx[c] >= long(g.size[c]))
    {
      return 0.0;
    }
  }
  return values[g.LinearIndex(std::size_t(idx[0]), std::size_t(idx[1]), std::size_t(idx[2]))];
}

/// One seed per open vessel end: the centre of its rim moved 3 mm into the lumen.
std::vector<Point3> EndSeeds(vtkPolyData* surface,
  const ImageGeometry& g,
  const std::vector<float>& fraction)
{
  vtkNew<vtkFeatureEdges> edges;
  edges->SetInputData(surface);
  edges->BoundaryEdgesOn();
  edges->FeatureEdgesOff();
  edges->NonManifoldEdgesOff();
  edges->ManifoldEdgesOff();
  vtkNew<vtkStripper> stripper;
  stripper->SetInputConnection(edges->GetOutputPort());
  stripper->JoinContiguousSegmentsOn();
  stripper->Update();
  vtkPolyData* loops = stripper->GetOutput();
  std::vector<Point3> seeds;
  vtkCellArray* lines = loops->GetLines();
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  for (lines->InitTraversal(); lines->GetNextCell(npts, ids);)
  {
    if (npts < 3)
    {
      continue;
    }
    Point3 centre{ { 0, 0, 0 } };
    Point3 normal{ { 0, 0, 0 } };
    for (vtkIdType i = 0; i < npts; ++i)
    {
      double a[3], b[3];
      loops->GetPoint(ids[i], a);
      loops->GetPoint(ids[(i + 1) % npts], b);
      for (int c = 0; c < 3; ++c)
      {
        centre[c] += a[c] / double(npts);
      }
      // Newell's method: the normal of a closed, roughly planar loop.
      normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
      normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
      normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    const double length =
      std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    if (length <= 0.0)
    {
      continue;
    }
    for (double sign : { 1.0, -1.0 })
    {
      Point3 p;
      for (int c = 0; c < 3; ++c)
      {
        p[c] = centre[c] + sign * 3.0 * normal[c] / length;
      }
      if (Sample(g, fraction, p) > 0.99)
      {
        seeds.push_back(p);
        break;
      }
    }
  }
  return seeds;
}

} // namespace

Phantom MakeVesselPhantom(vtkPolyData* surface,
  const PhantomParameters& p,
  const ProgressReporter& progress)
{
  Require(p.spacing >= 0.1 && p.spacing <= 2.0, "spacing: must be in [0.1, 2] mm");
  Require(p.margin >= 0.0 && p.margin <= 50.0, "margin: must be in [0, 50] mm");
  Require(p.psfFwhm >= 0.0 && p.psfFwhm <= 5.0, "psfFwhm: must be in [0, 5] mm");
  Require(p.biasAmplitude >= 0.0 && p.biasAmplitude <= 0.5, "biasAmplitude: must be in [0, 0.5]");
  Require(p.noiseSigma >= 0.0 && p.noiseSigma <= 200.0, "noiseSigma: must be in [0, 200]");
  Require(p.supersampling >= 1 && p.supersampling <= 4, "supersampling: must be in [1, 4]");
  Require(std::isfinite(p.vesselIntensity) && std::isfinite(p.backgroundIntensity),
    "intensities: must be finite");
  if (!surface || surface->GetNumberOfPolys() == 0)
  {
    throw ParameterError("phantom: the surface has no polygons");
  }

  Phantom phantom;
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputData(surface);
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(triangulate->GetOutputPort());
  clean->Update();
  vtkNew<vtkPolyData> input;
  input->DeepCopy(clean->GetOutput());
  const vtkIdType inputCells = input->GetNumberOfCells();

  // Close the cut vessel ends with flat caps so that the stencil sees a solid.
  vtkNew<vtkFillHolesFilter> fill;
  fill->SetInputData(input);
  fill->SetHoleSize(1.0e6);
  vtkNew<vtkTriangleFilter> triangulateCaps;
  triangulateCaps->SetInputConnection(fill->GetOutputPort());
  triangulateCaps->Update();
  phantom.cappedTruth = vtkSmartPointer<vtkPolyData>::New();
  phantom.cappedTruth->DeepCopy(triangulateCaps->GetOutput());
  phantom.caps = vtkSmartPointer<vtkPolyData>::New();
  {
    vtkNew<vtkCellArray> caps;
    vtkIdType npts = 0;
    const vtkIdType* ids = nullptr;
    vtkCellArray* polys = phantom.cappedTruth->GetPolys();
    vtkIdType cellId = 0;
    for (polys->InitTraversal(); polys->GetNextCell(npts, ids); ++cellId)
    {
      if (cellId >= inputCells)
      {
        caps->InsertNextCell(npts, ids);
      }
    }
    phantom.caps->SetPoints(phantom.cappedTruth->GetPoints());
    phantom.caps->SetPolys(caps);
  }
  progress.Report("phantom", 0.1);
  progress.ThrowIfCancelled("phantom");

  double bounds[6];
  phantom.cappedTruth->GetBounds(bounds);
  ImageGeometry& g = phantom.volume.geometry;
  const double h = p.spacing;
  for (int c = 0; c < 3; ++c)
  {
    g.spacing[c] = h;
    g.origin[c] = bounds[2 * c] - p.margin;
    g.size[c] = static_cast<std::size_t>(
                  std::ceil((bounds[2 * c + 1] - bounds[2 * c] + 2.0 * p.margin) / h)) +
      1;
  }
  const int s = p.supersampling;
  if (double(g.VoxelCount()) * s * s * s > 2.0e8)
  {
    throw ParameterError("phantom: more than 2e8 sub-voxels, increase the spacing");
  }

  // Voxelize at spacing h / s; sub-voxel m of voxel i is centred at origin + (i - 1/2)h + (m +
  // 1/2)h/s.
  const double hf = h / s;
  vtkNew<vtkPolyDataToImageStencil> stencil;
  stencil->SetInputData(phantom.cappedTruth);
  stencil->SetOutputSpacing(hf, hf, hf);
  stencil->SetOutputOrigin(g.origin[0] - 0.5 * h + 0.5 * hf,
    g.origin[1] - 0.5 * h + 0.5 * hf,
    g.origin[2] - 0.5 * h + 0.5 * hf);
  stencil->SetOutputWholeExtent(
    0, int(g.size[0]) * s - 1, 0, int(g.size[1]) * s - 1, 0, int(g.size[2]) * s - 1);
  stencil->SetTolerance(0.0);
  vtkNew<vtkImageStencilToImage> toImage;
  toImage->SetInputConnection(stencil->GetOutputPort());
  toImage->SetInsideValue(1);
  toImage->SetOutsideValue(0);
  toImage->SetOutputScalarTypeToUnsignedChar();
  toImage->Update();
  const auto* fine = static_cast<const unsigned char*>(
    toImage->GetOutput()->GetPointData()->GetScalars()->GetVoidPointer(0));
  progress.Report("phantom", 0.4);
  progress.ThrowIfCancelled("phantom");

  const std::size_t fx = g.size[0] * std::size_t(s);
  const std::size_t fy = g.size[1] * std::size_t(s);
  std::vector<float> fraction(g.VoxelCount(), 0.0f);
  const float weight = 1.0f / float(s * s * s);
  for (std::size_t k = 0; k < g.size[2] * std::size_t(s); ++k)
  {
    for (std::size_t j = 0; j < fy; ++j)
    {
      const unsigned char* row = fine + fx * (j + fy * k);
      float* out = fraction.data() + g.LinearIndex(0, j / std::size_t(s), k / std::size_t(s));
      for (std::size_t i = 0; i < fx; ++i)
      {
        out[i / std::size_t(s)] += row[i] ? weight : 0.0f;
      }
    }
  }
  progress.Report("phantom", 0.5);
  progress.ThrowIfCancelled("phantom");

  const double sigma = p.psfFwhm / (2.0 * std::sqrt(2.0 * std::log(2.0)));
  const std::vector<float> blurred = Blur(g, fraction, sigma);
  progress.Report("phantom", 0.7);

  std::mt19937 random(p.randomSeed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  phantom.volume.voxels.resize(g.VoxelCount());
  for (std::size_t k = 0; k < g.size[2]; ++k)
  {
    const double z = (double(k) + 0.5) / double(g.size[2]);
    for (std::size_t j = 0; j < g.size[1]; ++j)
    {
      const double y = (double(j) + 0.5) / double(g.size[1]);
      for (std::size_t i = 0; i < g.size[0]; ++i)
      {
        const double x = (double(i) + 0.5) / double(g.size[0]);
        const std::size_t n = g.LinearIndex(i, j, k);
        // A smooth field within [1 - a, 1 + a]: a tilt plus one slow oscillation.
        const double bias =
          1.0 + p.biasAmplitude * (0.6 * (2.0 * x - 1.0) + 0.4 * std::cos(M_PI * (y + 0.5 * z)));
        const double signal = bias *
          (p.backgroundIntensity +
            (p.vesselIntensity - p.backgroundIntensity) * double(blurred[n]));
        const double re = signal + p.noiseSigma * gauss(random);
        const double im = p.noiseSigma * gauss(random);
        phantom.volume.voxels[n] = float(std::sqrt(re * re + im * im));
      }
    }
  }
  progress.Report("phantom", 0.9);

  // Seed: the centre of the thickest part of the lumen.
  const std::vector<float> thick = Blur(g, fraction, 1.5);
  const std::size_t best =
    std::size_t(std::max_element(thick.begin(), thick.end()) - thick.begin());
  const std::size_t bi = best % g.size[0];
  const std::size_t bj = (best / g.size[0]) % g.size[1];
  const std::size_t bk = best / (g.size[0] * g.size[1]);
  phantom.seed = g.IndexToPhysical({ { double(bi), double(bj), double(bk) } });
  phantom.vesselSeeds = EndSeeds(input, g, fraction);
  phantom.midIntensity = 0.5 * (p.vesselIntensity + p.backgroundIntensity);
  progress.Report("phantom", 1.0);
  return phantom;
}

} // namespace bender
