// bender-cli segment and bender-cli phantom: their options (CLI11, CliParsing.h) and the runs;
// the workflows are bender::SegmentVolume and bender::MakePhantomVolume in modules/Logic.

#include "SegmentCommand.h"

#include "CliCommand.h"
#include "CliParsing.h"

#include "MeshIO.h"
#include "SegmentVolume.h"

#include <vtkPolyData.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <limits>
#include <memory>
#include <ostream>
#include <sstream>
#include <unistd.h>

namespace bender
{
namespace
{
const char* const SegmentDetails =
  "Segments the vessels of VOLUME and writes their lumen surface (LPS mm) to SURFACE (.stl "
  ".obj .ply .vtp .vtk .off).\n"
  "VOLUME: .nrrd .nhdr .nii .nii.gz .mha .mhd .vti, or a folder holding a DICOM series.\n"
  "\n"
  "example: bender-cli segment phantom.nii.gz -o vessel.vtp --seed 10.5,-20,31 --method "
  "vesselness\n"
  "\n"
  "exit status: 0 written, 1 bad input (unreadable volume, seed outside the volume or in the "
  "background), 2 usage error";

const char* const PhantomDetails =
  "Builds an MRA-like volume from a vessel surface (the ground truth): caps the open vessel "
  "ends, voxelizes, blurs with the point-spread function, adds a smooth intensity bias and "
  "Rician noise. Deterministic. VOLUME: .nrrd .nhdr .nii .nii.gz .mha .mhd .vti\n"
  "\n"
  "exit status: 0 written, 1 unreadable surface or write failure, 2 usage error";

const double Lowest = std::numeric_limits<double>::lowest();
const double Highest = std::numeric_limits<double>::max();

// What CLI11 reads as text for segment; SegmentRequest gets it in FinishSegmentRequest.
struct SegmentTexts
{
  std::vector<std::string> seeds;
  std::string method = "threshold";
  std::string fillHoles = "on";
  std::string extractor = "vtk";
};

struct SegmentState
{
  SegmentRequest request;
  SegmentTexts texts;
};

void AddSegmentOptions(CLI::App& segment, SegmentRequest& r, SegmentTexts& t)
{
  SegmentationParameters& s = r.segmentation;
  segment.add_option("VOLUME", r.input, "the volume (file, or folder of a DICOM series)")
    ->required();
  segment.add_option("-o,--output", r.output, "the surface file to write")
    ->required()
    ->type_name("SURFACE");
  OneOf(segment.add_option("--method",
          t.method,
          "threshold: intensity window + seeded region; vesselness: multi-scale Frangi "
          "vesselness, then seeded region"),
    { "threshold", "vesselness" })
    ->capture_default_str();
  segment.add_option("--lower", s.lower, "lower end of the lumen's intensity window")
    ->type_name("L")
    ->check(NumberIn(Lowest, Highest))
    ->capture_default_str();
  segment.add_option("--upper", s.upper, "upper end of the window (default: no upper end)")
    ->type_name("U")
    ->check(NumberIn(Lowest, Highest));
  AddPointsOption(segment,
    "--seed",
    t.seeds,
    "seed points, LPS mm (repeatable); the connected lumen that contains them is kept "
    "(default: the largest component)");
  OneOf(segment.add_option("--fill-holes", t.fillHoles, "fill cavities enclosed by the lumen"),
    { "on", "off" })
    ->capture_default_str();
  segment.add_option("--closing", s.closingRadius, "morphological closing radius, mm; 0 = off")
    ->type_name("R")
    ->check(NumberIn(0, 5))
    ->capture_default_str();
  segment.add_option("--min-radius", s.minRadius, "vesselness: smallest vessel radius, mm")
    ->type_name("R")
    ->check(NumberIn(0.1, 20))
    ->capture_default_str();
  segment.add_option("--max-radius", s.maxRadius, "vesselness: largest vessel radius, mm")
    ->type_name("R")
    ->check(NumberIn(0.1, 20))
    ->capture_default_str();
  segment.add_option("--scales", s.scales, "vesselness: number of scales")
    ->type_name("N")
    ->check(IntegerIn(1, 10))
    ->capture_default_str();
  segment
    .add_option("--vesselness-threshold",
      s.vesselnessThreshold,
      "vesselness: keep voxels >= T of the maximum, in (0, 1)")
    ->type_name("T")
    ->check(NumberAbove(0, 1))
    ->capture_default_str();
  segment
    .add_option("--level-set",
      s.levelSetIterations,
      "geodesic active contour refinement, N iterations; 0 = off")
    ->type_name("N")
    ->check(IntegerIn(0, 1000))
    ->capture_default_str();
  segment.add_option("--smoothing", r.surface.smoothing, "surface smoothing")
    ->type_name("S")
    ->check(NumberIn(0, 1))
    ->capture_default_str();
  segment
    .add_option("--target-triangles",
      r.surface.targetTriangles,
      "decimate to about N triangles; 0 = keep all")
    ->type_name("N")
    ->check(IntegerIn(0, 1e12))
    ->capture_default_str();
  OneOf(
    segment.add_option(
      "--extractor", t.extractor, "marching cubes: VTK flying edges or ITK BinaryMask3DMeshSource"),
    { "vtk", "itk" })
    ->capture_default_str();
  segment
    .add_option("--series",
      r.read.dicomSeriesUid,
      "DICOM folder with several series: the one to read (default: the one with the most "
      "slices, named on stderr)")
    ->type_name("UID");
  segment.add_flag("-q,--quiet", r.quiet, "no progress output");
}

// The request completed from its texts and checked as a whole; throws ParameterError.
void FinishSegmentRequest(SegmentRequest& r, const SegmentTexts& t)
{
  for (const Point3& p : Points(t.seeds))
  {
    r.segmentation.seeds.push_back(p);
  }
  r.segmentation.method =
    t.method == "vesselness" ? SegmentationMethod::Vesselness : SegmentationMethod::Threshold;
  r.segmentation.fillHoles = t.fillHoles == "on";
  r.surface.extractor = t.extractor == "itk" ? SurfaceExtractor::Itk : SurfaceExtractor::Vtk;
  ValidateSegmentationParameters(r.segmentation);
  r.surface.seeds = r.segmentation.seeds;
}

void AddPhantomOptions(CLI::App& phantom, PhantomRequest& r)
{
  PhantomParameters& p = r.phantom;
  phantom.add_option("SURFACE", r.input, "the vessel surface (the ground truth)")->required();
  phantom.add_option("-o,--output", r.output, "the volume to write")
    ->required()
    ->type_name("VOLUME");
  phantom.add_option("--spacing", p.spacing, "voxel size, mm")
    ->type_name("H")
    ->check(NumberIn(0.1, 2))
    ->capture_default_str();
  phantom.add_option("--psf", p.psfFwhm, "point-spread full width at half maximum, mm")
    ->type_name("FWHM")
    ->check(NumberIn(0, 5))
    ->capture_default_str();
  phantom
    .add_option("--noise",
      p.noiseSigma,
      "Rician noise sigma (lumen " + std::to_string(int(p.vesselIntensity)) + ", background " +
        std::to_string(int(p.backgroundIntensity)) + ")")
    ->type_name("SIGMA")
    ->check(NumberIn(0, 200))
    ->capture_default_str();
  phantom.add_option("--bias", p.biasAmplitude, "relative bias amplitude")
    ->type_name("A")
    ->check(NumberIn(0, 0.5))
    ->capture_default_str();
  phantom.add_option("--margin", p.margin, "background around the surface, mm")
    ->type_name("M")
    ->check(NumberIn(0, 50))
    ->capture_default_str();
  phantom.add_option("--random-seed", p.randomSeed, "noise generator seed")
    ->type_name("N")
    ->check(IntegerIn(0, 4294967295.0))
    ->capture_default_str();
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

int RunSegment(SegmentState state, std::ostream& out, std::ostream& err)
{
  SegmentRequest& request = state.request;
  try
  {
    FinishSegmentRequest(request, state.texts);
  }
  catch (const ParameterError& e)
  {
    return UsageError(err, "segment", e.what());
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
      err << "bender-cli segment: warning: " << result.warning
          << " Run again with a lower --lower.\n";
    return 0;
  }
  catch (const std::exception& e)
  {
    terminal.Finish();
    err << "bender-cli segment: " << ErrorLine(e.what()) << "\n";
    return 1;
  }
}

int RunPhantom(const PhantomRequest& request, std::ostream& out, std::ostream& err)
{
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
    err << "bender-cli phantom: " << ErrorLine(e.what()) << "\n";
    return 1;
  }
}

// Parses the words after a command's name with that command's options alone (`add` adds them
// to the subcommand): a CLI11 error becomes a ParameterError with its one-line message.
// Returns false when --help was given.
bool ParseAlone(const char* name,
  const std::vector<std::string>& args,
  const std::function<void(CLI::App&)>& add)
{
  const std::unique_ptr<CLI::App> cli = NewCliApp();
  add(*cli->add_subcommand(name));
  std::vector<std::string> words = { name };
  words.insert(words.end(), args.begin(), args.end());
  words = SplitPointLists(words);
  try
  {
    std::vector<std::string> reversed(words.rbegin(), words.rend());
    cli->parse(reversed);
  }
  catch (const CLI::CallForHelp&)
  {
    return false;
  }
  catch (const CLI::ParseError& e)
  {
    throw ParameterError(e.what());
  }
  return true;
}
} // namespace

SegmentRequest ParseSegmentArguments(const std::vector<std::string>& args)
{
  SegmentState state;
  if (!ParseAlone("segment",
        args,
        [&state](CLI::App& segment) { AddSegmentOptions(segment, state.request, state.texts); }))
  {
    state.request.help = true;
    return state.request;
  }
  FinishSegmentRequest(state.request, state.texts);
  return state.request;
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

void AddSegmentCommand(CLI::App& cli, std::ostream& out, std::ostream& err)
{
  auto state = std::make_shared<SegmentState>();
  CLI::App* segment = AddCommand(cli,
    "segment",
    "segment the vessels of a volume and extract their surface",
    SegmentDetails,
    [state, &out, &err] { return RunSegment(*state, out, err); });
  AddSegmentOptions(*segment, state->request, state->texts);
}

void AddPhantomCommand(CLI::App& cli, std::ostream& out, std::ostream& err)
{
  auto request = std::make_shared<PhantomRequest>();
  CLI::App* phantom = AddCommand(cli,
    "phantom",
    "build the MRA-like demo volume from a vessel surface",
    PhantomDetails,
    [request, &out, &err] { return RunPhantom(*request, out, err); });
  AddPhantomOptions(*phantom, *request);
}

int RunSegmentCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err)
{
  return RunAlone(
    "segment", args, out, err, [&](CLI::App& cli) { AddSegmentCommand(cli, out, err); });
}

int RunPhantomCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err)
{
  return RunAlone(
    "phantom", args, out, err, [&](CLI::App& cli) { AddPhantomCommand(cli, out, err); });
}

} // namespace bender
