// bender-cli export IN -o OUT [--cap] [--patches single|solids|files] [--frame lps|ras]:
// CFD-ready STL of a vessel surface.

#include "CliCommands.h"
#include "CliParsing.h"

#include "ExportSurface.h"

#include <vtkOutputWindow.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace
{
const char* const Usage =
  "usage: bender-cli export IN_MESH -o OUT.stl [options]\n"
  "\n"
  "Writes IN_MESH as STL for CFD meshers. Coordinates are taken to be LPS millimetres (the\n"
  "frame of Bender's segmentations); every STL header states the frame and unit.\n"
  "\n"
  "options:\n"
  "  -o, --output OUT.stl      the output (required; never the input). OUT.vtp writes the\n"
  "                            VTK form, which keeps the PatchId cell labels\n"
  "  --cap                     close planar-ish open ends (vessel inlets/outlets) with flat\n"
  "                            caps labelled cap_1..cap_n (wall = the rest)\n"
  "  --planarity F             a loop is capped when its points lie within F x its\n"
  "                            diameter of a plane (default 0.1)\n"
  "  --patches single|solids|files\n"
  "                            single: one binary STL (default); solids: one ASCII STL with\n"
  "                            a named solid per patch (snappyHexMesh); files: one binary STL\n"
  "                            per patch, OUT_wall.stl, OUT_cap_1.stl, ...\n"
  "  --frame lps|ras           frame of the written coordinates (default lps; ras negates\n"
  "                            x and y)\n"
  "  --quiet                   print nothing on success\n"
  "  -h, --help                this help\n"
  "\n"
  "Patches come from the cell array PatchId (kept in .vtp files), or from --cap.\n"
  "exit status: 0 written, 1 bad input or write failure, 2 usage error\n";

int Fail(const std::string& message)
{
  std::fprintf(stderr, "bender-cli export: %s\n", message.c_str());
  return 1;
}
} // namespace

int RunExportCommand(const std::vector<std::string>& args)
{
  bender::CommandLine cli("export", Usage);
  std::vector<std::string> positional;
  std::string outPath, patches = "single", frame = "lps";
  bool quiet = false;
  bender::ExportSurfaceOptions options;
  cli.App.add_option("mesh", positional);
  cli.App.add_option("-o,--output", outPath);
  cli.App.add_flag("--cap", options.cap);
  cli.App.add_flag("--quiet", quiet);
  std::string planarity;
  cli.App.add_option("--planarity", planarity);
  cli.App.add_option("--patches", patches);
  cli.App.add_option("--frame", frame);
  if (const int status = cli.Parse(args); status >= 0)
  {
    return status;
  }
  if (!planarity.empty())
  {
    char* end = nullptr;
    options.planarity = std::strtod(planarity.c_str(), &end);
    if (end == planarity.c_str() || *end || !(options.planarity >= 0 && options.planarity <= 1))
    {
      return cli.UsageError("--planarity: '" + planarity + "' is not in [0, 1]");
    }
  }
  if (patches == "single")
  {
    options.patches = bender::StlPatchMode::Single;
  }
  else if (patches == "solids")
  {
    options.patches = bender::StlPatchMode::Solids;
  }
  else if (patches == "files")
  {
    options.patches = bender::StlPatchMode::Files;
  }
  else
  {
    return cli.UsageError("--patches: unknown value '" + patches + "'");
  }
  if (frame == "lps" || frame == "LPS")
  {
    options.frame = bender::StlFrame::LPS;
  }
  else if (frame == "ras" || frame == "RAS")
  {
    options.frame = bender::StlFrame::RAS;
  }
  else
  {
    return cli.UsageError("--frame: unknown value '" + frame + "'");
  }
  if (positional.size() != 1 || outPath.empty())
  {
    return cli.UsageError("expected IN_MESH -o OUT.stl");
  }
  std::string ext = outPath.size() >= 4 ? outPath.substr(outPath.size() - 4) : "";
  for (char& c : ext)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  if (ext != ".stl" && ext != ".vtp")
  {
    std::fprintf(
      stderr, "bender-cli export: %s: the output must be .stl (or .vtp)\n", outPath.c_str());
    return 2;
  }
  if (ext == ".vtp" &&
    (options.frame != bender::StlFrame::LPS || options.patches != bender::StlPatchMode::Single))
  {
    // The VTK form keeps the PatchId cell labels (wall 0, caps 1..n), in LPS.
    std::fprintf(stderr, "bender-cli export: .vtp output is written whole, in LPS\n");
    return 2;
  }
  const std::string& inPath = positional[0];
  options.output = outPath;
  options.protectedPath = inPath;
  options.sourceName = std::filesystem::path(inPath).filename().string();
  if (bender::SameFile(inPath, outPath))
  {
    return Fail(outPath + ": refusing to overwrite the input file; choose another output");
  }
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  vtkSmartPointer<vtkPolyData> mesh;
  try
  {
    mesh = bender::ReadMesh(inPath);
  }
  catch (const std::exception& e)
  {
    return Fail(e.what());
  }
  bender::ExportSurfaceResult result;
  try
  {
    result = bender::ExportSurface(mesh, options);
  }
  catch (const bender::Error& e)
  {
    return Fail(e.what());
  }
  if (!quiet)
  {
    if (options.cap)
    {
      std::printf("capped %d open end%s%s\n",
        result.caps,
        result.caps == 1 ? "" : "s",
        result.skippedLoops
          ? (", left " + std::to_string(result.skippedLoops) + " non-planar boundary loop(s) open")
              .c_str()
          : "");
    }
    bender::MeshCheckOptions checkOptions;
    checkOptions.selfIntersections = false;
    const auto report = bender::CheckMesh(result.surface, nullptr, checkOptions);
    for (const std::string& file : result.written)
    {
      std::printf("wrote %s\n", file.c_str());
    }
    std::printf("%lld triangles, %s%s\n",
      static_cast<long long>(report.triangles),
      report.closed ? "closed" : "open",
      report.closed ? (", volume " + std::to_string(std::abs(report.volume))).c_str() : "");
  }
  return 0;
}
