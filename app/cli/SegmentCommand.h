#ifndef bender_SegmentCommand_h
#define bender_SegmentCommand_h

// `bender-cli segment` and `bender-cli phantom` (part of bender_cli_commands, so that the tests
// run them in-process). The workflow itself is bender::SegmentVolume in modules/Logic.

#include "SegmentVolume.h"
#include "SurfaceExtraction.h"
#include "VesselPhantom.h"
#include "VesselSegmentation.h"
#include "VolumeIO.h"

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace bender
{

struct SegmentRequest
{
  std::string input;
  std::string output;
  VolumeReadOptions read;
  SegmentationParameters segmentation;
  SurfaceParameters surface;
  bool quiet = false;
  bool help = false;
};

struct PhantomRequest
{
  std::string input;
  std::string output;
  PhantomParameters phantom;
};

/// Parses the words after `segment` (the options of `bender-cli segment`). Throws
/// ParameterError with a one-line message; help is set for --help.
SegmentRequest ParseSegmentArguments(const std::vector<std::string>& args);

/// Reads, segments and extracts; the surface is in LPS mm. Timings of every stage (read,
/// segmentation, then the surface stages) are appended to the result's timings. `inform` is
/// told which series was read from a DICOM folder holding several when none was asked for
/// (SegmentVolumeOptions::inform).
SegmentVolumeResult RunSegmentPipeline(const SegmentRequest& request,
  const ProgressReporter& progress = {},
  const std::function<void(const std::string&)>& inform = {});

/// The whole commands, as `bender-cli segment|phantom ARGS` (CliCommand.h): help on `out` for
/// --help (exit 0); progress and errors on `err`; exit
/// status 0 on success, 1 on a processing error (bad input, seed outside the volume or in
/// background), 2 on a usage error. The output file is written atomically (never half-written).
int RunSegmentCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
int RunPhantomCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

} // namespace bender

#endif
