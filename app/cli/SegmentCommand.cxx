#include "SegmentCommand.h"

#include "MeshIO.h"
#include "SegmentVolume.h"

#include <CLI/CLI.hpp>

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

// Runs CLI11 on the words after the command name; a CLI11 error becomes a ParameterError with
// CLI11's one-line message. Returns false when --help was given (whatever else was wrong).
bool ParseWords(CLI::App& app, const std::vector<std::string>& args, const bool& help)
{
  try
  {
    std::vector<std::string> reversed(args.rbegin(), args.rend());
    app.parse(reversed);
  }
  catch (const CLI::ParseError& e)
  {
    if (help)
    {
      return false;
    }
    std::string what = e.what();
    while (!what.empty() && (what.back() == '\n' || what.back() == ' '))
    {
      what.pop_back();
    }
    throw ParameterError(what);
  }
  return !help;
}

// The value of an option given as text, as a number (same messages for every option).
void Number(const CLI::App& app, const char* option, const std::string& text, double& value)
{
  if (app.count(option))
  {
    value = ParseNumber(option, text);
  }
}

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
      reporter.onProgress = [this](const std::string& stage, double fraction)
      { this->Show(stage, fraction); };
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
    line << "  " << std::left << std::setw(18) << stage << std::right << std::setw(4) << percent
         << "%";
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
       "                             vesselness: multi-scale Frangi vesselness, then seeded "
       "region\n"
       "  --lower L, --upper U       intensity window of the lumen (default "
    << d.lower
    << ", +inf)\n"
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
       "  --level-set N              geodesic active contour refinement, N iterations (default 0 = "
       "off)\n"
       "  --smoothing S              surface smoothing, 0..1 (default "
    << s.smoothing
    << ")\n"
       "  --target-triangles N       decimate to about N triangles (default 0 = keep all)\n"
       "  --extractor vtk|itk        marching cubes: VTK flying edges (default) or ITK\n"
       "                             BinaryMask3DMeshSource\n"
       "  --series UID               DICOM folder with several series: the one to read\n"
       "                             (default: the one with the most slices, named on stderr)\n"
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
    << "  --noise SIGMA         Rician noise sigma (default " << d.noiseSigma << "; lumen "
    << d.vesselIntensity << ", background " << d.backgroundIntensity << ")\n"
    << "  --bias A              relative bias amplitude, 0..0.5 (default " << d.biasAmplitude
    << ")\n"
    << "  --margin M            background around the surface, mm (default " << d.margin << ")\n"
    << "  --random-seed N       noise generator seed (default " << d.randomSeed << ")\n"
    << "  -h, --help            this help\n";
  return u.str();
}

SegmentRequest ParseSegmentArguments(const std::vector<std::string>& args)
{
  SegmentRequest r;
  CLI::App app("", "bender-cli segment");
  app.set_help_flag();
  app.add_flag("-h,--help", r.help);
  std::vector<std::string> positional, seeds;
  std::string method, lower, upper, fillHoles, closing, minRadius, maxRadius, scales, threshold,
    levelSet, smoothing, targetTriangles, extractor;
  app.add_option("volume", positional);
  app.add_option("-o,--output", r.output);
  app.add_option("--method", method);
  app.add_option("--lower", lower);
  app.add_option("--upper", upper);
  // --seed x,y,z [x,y,z ...], repeatable.
  app.add_option("--seed", seeds)->allow_extra_args(false);
  app.add_option("--fill-holes", fillHoles);
  app.add_option("--closing", closing);
  app.add_option("--min-radius", minRadius);
  app.add_option("--max-radius", maxRadius);
  app.add_option("--scales", scales);
  app.add_option("--vesselness-threshold", threshold);
  app.add_option("--level-set", levelSet);
  app.add_option("--smoothing", smoothing);
  app.add_option("--target-triangles", targetTriangles);
  app.add_option("--extractor", extractor);
  app.add_option("--series", r.read.dicomSeriesUid);
  app.add_flag("-q,--quiet", r.quiet);
  // "--seed x,y,z [x,y,z ...]": every point is passed as "--seed=x,y,z" so that negative
  // coordinates are never taken for options and the word after the points stays positional.
  std::vector<std::string> words;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    if (args[i] != "--seed" || i + 1 >= args.size())
    {
      words.push_back(args[i]);
      continue;
    }
    words.push_back("--seed=" + args[++i]);
    Point3 p{};
    while (i + 1 < args.size() && ParsePoint(args[i + 1], p))
    {
      words.push_back("--seed=" + args[++i]);
    }
  }
  if (!ParseWords(app, words, r.help))
  {
    r.help = true;
    return r;
  }
  for (const std::string& text : seeds)
  {
    Point3 p{};
    if (!ParsePoint(text, p))
    {
      throw ParameterError("--seed: expected x,y,z in mm, got '" + text + "'");
    }
    r.segmentation.seeds.push_back(p);
  }
  if (app.count("--method"))
  {
    if (method == "threshold")
    {
      r.segmentation.method = SegmentationMethod::Threshold;
    }
    else if (method == "vesselness")
    {
      r.segmentation.method = SegmentationMethod::Vesselness;
    }
    else
    {
      throw ParameterError("--method: '" + method + "' is not threshold or vesselness");
    }
  }
  Number(app, "--lower", lower, r.segmentation.lower);
  Number(app, "--upper", upper, r.segmentation.upper);
  if (app.count("--fill-holes"))
  {
    if (fillHoles != "on" && fillHoles != "off")
    {
      throw ParameterError("--fill-holes: expected on or off, got '" + fillHoles + "'");
    }
    r.segmentation.fillHoles = fillHoles == "on";
  }
  Number(app, "--closing", closing, r.segmentation.closingRadius);
  Number(app, "--min-radius", minRadius, r.segmentation.minRadius);
  Number(app, "--max-radius", maxRadius, r.segmentation.maxRadius);
  if (app.count("--scales"))
  {
    r.segmentation.scales = int(ParseNumber("--scales", scales));
  }
  Number(app, "--vesselness-threshold", threshold, r.segmentation.vesselnessThreshold);
  if (app.count("--level-set"))
  {
    r.segmentation.levelSetIterations = int(ParseNumber("--level-set", levelSet));
  }
  Number(app, "--smoothing", smoothing, r.surface.smoothing);
  if (app.count("--target-triangles"))
  {
    const double n = ParseNumber("--target-triangles", targetTriangles);
    if (n < 0 || n != std::floor(n))
    {
      throw ParameterError("--target-triangles: expected a count >= 0");
    }
    r.surface.targetTriangles = std::size_t(n);
  }
  if (app.count("--extractor"))
  {
    if (extractor == "vtk")
    {
      r.surface.extractor = SurfaceExtractor::Vtk;
    }
    else if (extractor == "itk")
    {
      r.surface.extractor = SurfaceExtractor::Itk;
    }
    else
    {
      throw ParameterError("--extractor: '" + extractor + "' is not vtk or itk");
    }
  }
  if (positional.size() > 1)
  {
    throw ParameterError("unexpected argument '" + positional[1] + "' (one VOLUME only)");
  }
  if (!positional.empty())
  {
    r.input = positional[0];
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
  CLI::App app("", "bender-cli phantom");
  app.set_help_flag();
  app.add_flag("-h,--help", r.help);
  std::vector<std::string> positional;
  std::string spacing, psf, noise, bias, margin, randomSeed;
  app.add_option("surface", positional);
  app.add_option("-o,--output", r.output);
  app.add_option("--spacing", spacing);
  app.add_option("--psf", psf);
  app.add_option("--noise", noise);
  app.add_option("--bias", bias);
  app.add_option("--margin", margin);
  app.add_option("--random-seed", randomSeed);
  if (!ParseWords(app, args, r.help))
  {
    r.help = true;
    return r;
  }
  Number(app, "--spacing", spacing, r.phantom.spacing);
  Number(app, "--psf", psf, r.phantom.psfFwhm);
  Number(app, "--noise", noise, r.phantom.noiseSigma);
  Number(app, "--bias", bias, r.phantom.biasAmplitude);
  Number(app, "--margin", margin, r.phantom.margin);
  if (app.count("--random-seed"))
  {
    const double n = ParseNumber("--random-seed", randomSeed);
    if (n < 0 || n > 4294967295.0 || n != std::floor(n))
    {
      throw ParameterError("--random-seed: expected an integer in [0, 2^32)");
    }
    r.phantom.randomSeed = std::uint32_t(n);
  }
  if (positional.size() > 1)
  {
    throw ParameterError("unexpected argument '" + positional[1] + "' (one SURFACE only)");
  }
  if (!positional.empty())
  {
    r.input = positional[0];
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

SegmentVolumeResult RunSegmentPipeline(const SegmentRequest& request,
  const ProgressReporter& progress,
  const std::function<void(const std::string&)>& inform)
{
  SegmentVolumeOptions options;
  options.inform = inform;
  options.input = request.input;
  options.read = request.read;
  options.segmentation = request.segmentation;
  options.surface = request.surface;
  options.progress = progress;
  return SegmentVolume(options);
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
    // A DICOM folder with several series and no --series: the largest is read and named in
    // one line (before any progress is drawn), as the window does.
    const SegmentVolumeResult result = RunSegmentPipeline(request,
      terminal.Reporter(),
      [&err](const std::string& note) { err << "bender-cli segment: " << note << "\n"; });
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
        << (result.boundaryEdges == 0 ? std::string("closed")
                                      : std::to_string(result.boundaryEdges) + " open edges")
        << ", " << std::fixed << std::setprecision(2) << total << " s\n";
    if (!result.warning.empty())
      err << "bender-cli segment: warning: " << result.warning << "\n";
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
    PhantomVolumeOptions options;
    options.input = request.input;
    options.output = request.output;
    options.phantom = request.phantom;
    const Phantom phantom = MakePhantomVolume(options);
    const ImageGeometry& g = phantom.volume.geometry;
    out << request.output << ": " << g.size[0] << "x" << g.size[1] << "x" << g.size[2]
        << " voxels of " << g.spacing[0] << " mm, lumen " << request.phantom.vesselIntensity
        << ", background " << request.phantom.backgroundIntensity << "\n"
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
