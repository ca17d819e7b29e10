#include "SegmentCommand.h"

#include "MeshIO.h"

#include <vtkPolyData.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <unistd.h>

namespace bender
{
namespace
{

double ParseNumber(const std::string& option, const std::string& text)
{
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value))
  {
    throw ParameterError(option + ": '" + text + "' is not a number");
  }
  return value;
}

bool ParsePoint(const std::string& text, Point3& point)
{
  std::stringstream s(text);
  std::string part;
  int n = 0;
  while (std::getline(s, part, ','))
  {
    char* end = nullptr;
    const double v = std::strtod(part.c_str(), &end);
    if (n >= 3 || part.empty() || end != part.c_str() + part.size() || !std::isfinite(v))
    {
      return false;
    }
    point[std::size_t(n++)] = v;
  }
  return n == 3;
}

class ArgumentCursor
{
public:
  explicit ArgumentCursor(const std::vector<std::string>& args)
    : Args(args)
  {
  }
  bool Done() const { return this->Next >= this->Args.size(); }
  const std::string& Take() { return this->Args[this->Next++]; }
  const std::string* Peek() const { return this->Done() ? nullptr : &this->Args[this->Next]; }
  std::string Value(const std::string& option)
  {
    if (this->Done())
    {
      throw ParameterError(option + ": missing value");
    }
    return this->Take();
  }
  double Number(const std::string& option) { return ParseNumber(option, this->Value(option)); }

private:
  const std::vector<std::string>& Args;
  std::size_t Next = 0;
};

/// Prints "stage  NN%" lines; on a terminal they overwrite each other.
class TerminalProgress
{
public:
  TerminalProgress(std::ostream& err, bool quiet)
    : Err(err)
    , Quiet(quiet)
    , Tty(isatty(STDERR_FILENO) != 0)
  {
  }
  ProgressReporter Reporter()
  {
    ProgressReporter reporter;
    if (!this->Quiet)
    {
      reporter.onProgress = [this](const std::string& stage, double fraction) { this->Show(stage, fraction); };
    }
    return reporter;
  }
  void Finish()
  {
    if (this->Tty && !this->Stage.empty())
    {
      this->Err << "\n";
    }
  }

private:
  void Show(const std::string& stage, double fraction)
  {
    const int percent = int(std::lround(100.0 * std::clamp(fraction, 0.0, 1.0)));
    if (stage == this->Stage && percent < this->Percent + 10 && percent != 100)
    {
      return;
    }
    if (stage == this->Stage && percent == this->Percent)
    {
      return;
    }
    this->Stage = stage;
    this->Percent = percent;
    std::ostringstream line;
    line << "  " << std::left << std::setw(18) << stage << std::right << std::setw(4) << percent << "%";
    if (this->Tty)
    {
      this->Err << "\r" << line.str() << std::flush;
    }
    else if (percent == 100)
    {
      this->Err << line.str() << "\n";
    }
  }

  std::ostream& Err;
  bool Quiet;
  bool Tty;
  std::string Stage;
  int Percent = -100;
};

std::string FormatPoint(const Point3& p)
{
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << p[0] << "," << p[1] << "," << p[2];
  return s.str();
}

} // namespace

std::string SegmentUsage()
{
  const SegmentationParameters d;
  const SurfaceParameters s;
  std::ostringstream u;
  u << "usage: bender-cli segment VOLUME -o SURFACE [options]\n"
       "\n"
       "Segments the vessels of VOLUME and writes their lumen surface (LPS mm) to SURFACE\n"
       "(.stl .obj .ply .vtp .vtk .off).\n"
       "VOLUME: .nrrd .nhdr .nii .nii.gz .mha .mhd .vti, or a folder holding a DICOM series.\n"
       "\n"
       "options:\n"
       "  -o, --output SURFACE       the surface file to write (required)\n"
       "  --method threshold|vesselness\n"
       "                             threshold: intensity window + seeded region (default);\n"
       "                             vesselness: multi-scale Frangi vesselness, then seeded region\n"
       "  --lower L, --upper U       intensity window of the lumen (default "
    << d.lower << ", +inf)\n"
       "  --seed x,y,z [x,y,z ...]   seed points, LPS mm (repeatable); the connected lumen that\n"
       "                             contains them is kept. Default: the largest component\n"
       "  --fill-holes on|off        fill cavities enclosed by the lumen (default on)\n"
       "  --closing R                morphological closing radius, mm, 0..5 (default 0 = off)\n"
       "  --min-radius R, --max-radius R\n"
       "                             vesselness: vessel radii, mm (default "
    << d.minRadius << ", " << d.maxRadius
    << ")\n"
       "  --scales N                 vesselness: number of scales, 1..10 (default "
    << d.scales
    << ")\n"
       "  --vesselness-threshold T   vesselness: keep voxels >= T of the maximum, (0,1) (default "
    << d.vesselnessThreshold
    << ")\n"
       "  --level-set N              geodesic active contour refinement, N iterations (default 0 = off)\n"
       "  --smoothing S              surface smoothing, 0..1 (default "
    << s.smoothing
    << ")\n"
       "  --target-triangles N       decimate to about N triangles (default 0 = keep all)\n"
       "  --extractor vtk|itk        marching cubes: VTK flying edges (default) or ITK\n"
       "                             BinaryMask3DMeshSource\n"
       "  --series UID               DICOM folder with several series: the one to read\n"
       "  -q, --quiet                no progress output\n"
       "  -h, --help                 this help\n";
  return u.str();
}

std::string PhantomUsage()
{
  const PhantomParameters d;
  std::ostringstream u;
  u << "usage: bender-cli phantom SURFACE -o VOLUME [options]\n"
       "\n"
       "Builds an MRA-like volume from a vessel surface (the ground truth): caps the open vessel\n"
       "ends, voxelizes, blurs with the point-spread function, adds a smooth intensity bias and\n"
       "Rician noise. Deterministic. VOLUME: .nrrd .nhdr .nii .nii.gz .mha .mhd .vti\n"
       "\n"
       "options:\n"
       "  -o, --output VOLUME   the volume to write (required)\n"
       "  --spacing H           voxel size, mm, 0.1..2 (default "
    << d.spacing << ")\n"
    << "  --psf FWHM            point-spread full width at half maximum, mm (default " << d.psfFwhm
    << ")\n"
    << "  --noise SIGMA         Rician noise sigma (default " << d.noiseSigma
    << "; lumen " << d.vesselIntensity << ", background " << d.backgroundIntensity << ")\n"
    << "  --bias A              relative bias amplitude, 0..0.5 (default " << d.biasAmplitude << ")\n"
    << "  --margin M            background around the surface, mm (default " << d.margin << ")\n"
    << "  --random-seed N       noise generator seed (default " << d.randomSeed << ")\n"
    << "  -h, --help            this help\n";
  return u.str();
}

SegmentRequest ParseSegmentArguments(const std::vector<std::string>& args)
{
  SegmentRequest r;
  ArgumentCursor cursor(args);
  while (!cursor.Done())
  {
    const std::string a = cursor.Take();
    if (a == "-h" || a == "--help")
    {
      r.help = true;
      return r;
    }
    else if (a == "-o" || a == "--output")
    {
      r.output = cursor.Value(a);
    }
    else if (a == "--method")
    {
      const std::string m = cursor.Value(a);
      if (m == "threshold")
      {
        r.segmentation.method = SegmentationMethod::Threshold;
      }
      else if (m == "vesselness")
      {
        r.segmentation.method = SegmentationMethod::Vesselness;
      }
      else
      {
        throw ParameterError("--method: '" + m + "' is not threshold or vesselness");
      }
    }
    else if (a == "--lower")
    {
      r.segmentation.lower = cursor.Number(a);
    }
    else if (a == "--upper")
    {
      r.segmentation.upper = cursor.Number(a);
    }
    else if (a == "--seed")
    {
      Point3 p{};
      const std::string text = cursor.Value(a);
      if (!ParsePoint(text, p))
      {
        throw ParameterError("--seed: expected x,y,z in mm, got '" + text + "'");
      }
      r.segmentation.seeds.push_back(p);
      while (cursor.Peek() && ParsePoint(*cursor.Peek(), p))
      {
        cursor.Take();
        r.segmentation.seeds.push_back(p);
      }
    }
    else if (a == "--fill-holes")
    {
      const std::string v = cursor.Value(a);
      if (v != "on" && v != "off")
      {
        throw ParameterError("--fill-holes: expected on or off, got '" + v + "'");
      }
      r.segmentation.fillHoles = v == "on";
    }
    else if (a == "--closing")
    {
      r.segmentation.closingRadius = cursor.Number(a);
    }
    else if (a == "--min-radius")
    {
      r.segmentation.minRadius = cursor.Number(a);
    }
    else if (a == "--max-radius")
    {
      r.segmentation.maxRadius = cursor.Number(a);
    }
    else if (a == "--scales")
    {
      r.segmentation.scales = int(cursor.Number(a));
    }
    else if (a == "--vesselness-threshold")
    {
      r.segmentation.vesselnessThreshold = cursor.Number(a);
    }
    else if (a == "--level-set")
    {
      r.segmentation.levelSetIterations = int(cursor.Number(a));
    }
    else if (a == "--smoothing")
    {
      r.surface.smoothing = cursor.Number(a);
    }
    else if (a == "--target-triangles")
    {
      const double n = cursor.Number(a);
      if (n < 0 || n != std::floor(n))
      {
        throw ParameterError("--target-triangles: expected a count >= 0");
      }
      r.surface.targetTriangles = std::size_t(n);
    }
    else if (a == "--extractor")
    {
      const std::string e = cursor.Value(a);
      if (e == "vtk")
      {
        r.surface.extractor = SurfaceExtractor::Vtk;
      }
      else if (e == "itk")
      {
        r.surface.extractor = SurfaceExtractor::Itk;
      }
      else
      {
        throw ParameterError("--extractor: '" + e + "' is not vtk or itk");
      }
    }
    else if (a == "--series")
    {
      r.read.dicomSeriesUid = cursor.Value(a);
    }
    else if (a == "-q" || a == "--quiet")
    {
      r.quiet = true;
    }
    else if (!a.empty() && a[0] == '-' && a.size() > 1)
    {
      throw ParameterError("unknown option '" + a + "'");
    }
    else if (r.input.empty())
    {
      r.input = a;
    }
    else
    {
      throw ParameterError("unexpected argument '" + a + "' (one VOLUME only)");
    }
  }
  if (r.input.empty())
  {
    throw ParameterError("missing VOLUME");
  }
  if (r.output.empty())
  {
    throw ParameterError("missing -o SURFACE");
  }
  if (!(r.surface.smoothing >= 0.0 && r.surface.smoothing <= 1.0))
  {
    throw ParameterError("--smoothing: must be in [0, 1]");
  }
  ValidateSegmentationParameters(r.segmentation);
  r.surface.seeds = r.segmentation.seeds;
  return r;
}

PhantomRequest ParsePhantomArguments(const std::vector<std::string>& args)
{
  PhantomRequest r;
  ArgumentCursor cursor(args);
  while (!cursor.Done())
  {
    const std::string a = cursor.Take();
    if (a == "-h" || a == "--help")
    {
      r.help = true;
      return r;
    }
    else if (a == "-o" || a == "--output")
    {
      r.output = cursor.Value(a);
    }
    else if (a == "--spacing")
    {
      r.phantom.spacing = cursor.Number(a);
    }
    else if (a == "--psf")
    {
      r.phantom.psfFwhm = cursor.Number(a);
    }
    else if (a == "--noise")
    {
      r.phantom.noiseSigma = cursor.Number(a);
    }
    else if (a == "--bias")
    {
      r.phantom.biasAmplitude = cursor.Number(a);
    }
    else if (a == "--margin")
    {
      r.phantom.margin = cursor.Number(a);
    }
    else if (a == "--random-seed")
    {
      const double n = cursor.Number(a);
      if (n < 0 || n > 4294967295.0 || n != std::floor(n))
      {
        throw ParameterError("--random-seed: expected an integer in [0, 2^32)");
      }
      r.phantom.randomSeed = std::uint32_t(n);
    }
    else if (!a.empty() && a[0] == '-' && a.size() > 1)
    {
      throw ParameterError("unknown option '" + a + "'");
    }
    else if (r.input.empty())
    {
      r.input = a;
    }
    else
    {
      throw ParameterError("unexpected argument '" + a + "' (one SURFACE only)");
    }
  }
  if (r.input.empty())
  {
    throw ParameterError("missing SURFACE");
  }
  if (r.output.empty())
  {
    throw ParameterError("missing -o VOLUME");
  }
  return r;
}

SurfaceResult RunSegmentPipeline(const SegmentRequest& request, const ProgressReporter& progress)
{
  using Clock = std::chrono::steady_clock;
  const Clock::time_point t0 = Clock::now();
  const Volume volume = ReadVolume(request.input, request.read, progress);
  const Clock::time_point t1 = Clock::now();
  const LabelMap mask = SegmentVessels(volume, request.segmentation, progress);
  const Clock::time_point t2 = Clock::now();
  SurfaceResult result = ExtractSurface(mask, request.surface, progress);
  result.timings.insert(result.timings.begin(),
    { { "read", std::chrono::duration<double>(t1 - t0).count() },
      { "segmentation", std::chrono::duration<double>(t2 - t1).count() } });
  return result;
}

int RunSegmentCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err)
{
  SegmentRequest request;
  try
  {
    request = ParseSegmentArguments(args);
  }
  catch (const ParameterError& e)
  {
    err << "bender-cli segment: " << e.what() << " (see bender-cli segment --help)\n";
    return 2;
  }
  if (request.help)
  {
    out << SegmentUsage();
    return 0;
  }
  TerminalProgress terminal(err, request.quiet);
  try
  {
    if (SameFile(request.input, request.output))
    {
      throw ParameterError(request.output + ": output would overwrite the input");
    }
    const SurfaceResult result = RunSegmentPipeline(request, terminal.Reporter());
    MeshWriteOptions options;
    options.header = "bender segment: LPS mm";
    WriteMesh(result.surface, request.output, options);
    terminal.Finish();
    double total = 0.0;
    for (const StageTime& t : result.timings)
    {
      total += t.seconds;
    }
    out << request.output << ": " << result.surface->GetNumberOfPolys() << " triangles, "
        << result.surface->GetNumberOfPoints() << " points, LPS mm, "
        << (result.boundaryEdges == 0 ? std::string("closed") : std::to_string(result.boundaryEdges) + " open edges")
        << ", " << std::fixed << std::setprecision(2) << total << " s\n";
    return 0;
  }
  catch (const std::exception& e)
  {
    terminal.Finish();
    err << "bender-cli segment: " << e.what() << "\n";
    return 1;
  }
}

int RunPhantomCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err)
{
  PhantomRequest request;
  try
  {
    request = ParsePhantomArguments(args);
  }
  catch (const ParameterError& e)
  {
    err << "bender-cli phantom: " << e.what() << " (see bender-cli phantom --help)\n";
    return 2;
  }
  if (request.help)
  {
    out << PhantomUsage();
    return 0;
  }
  try
  {
    vtkSmartPointer<vtkPolyData> surface = ReadMesh(request.input);
    const Phantom phantom = MakeVesselPhantom(surface, request.phantom);
    const std::filesystem::path parent = std::filesystem::path(request.output).parent_path();
    if (!parent.empty())
    {
      std::filesystem::create_directories(parent);
    }
    // Write beside the target, then rename: no half-written volume on failure.
    const std::string ext = request.output.size() > 7 && request.output.substr(request.output.size() - 7) == ".nii.gz"
      ? ".nii.gz"
      : std::filesystem::path(request.output).extension().string();
    const std::string temporary = request.output + ".part" + ext;
    WriteVolume(phantom.volume, temporary);
    std::filesystem::rename(temporary, request.output);
    const ImageGeometry& g = phantom.volume.geometry;
    out << request.output << ": " << g.size[0] << "x" << g.size[1] << "x" << g.size[2] << " voxels of "
        << g.spacing[0] << " mm, lumen " << request.phantom.vesselIntensity << ", background "
        << request.phantom.backgroundIntensity << "\n"
        << "seed inside the lumen (LPS mm): " << FormatPoint(phantom.seed) << "\n"
        << "segment with: bender-cli segment " << request.output << " -o SURFACE --lower "
        << phantom.midIntensity << " --seed " << FormatPoint(phantom.seed) << "\n";
    return 0;
  }
  catch (const std::exception& e)
  {
    err << "bender-cli phantom: " << e.what() << "\n";
    return 1;
  }
}

} // namespace bender
