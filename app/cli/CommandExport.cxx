// bender-cli export IN -o OUT [--cap] [--patches single|solids|files] [--frame lps|ras]
// [--unit mm|m] [--patches-json]: CFD-ready surfaces for meshers (STL, VTP, TetGen).

#include "CliCommands.h"
#include "CliParsing.h"

#include "ExportSurface.h"
#include "MeshFormats.h"

#include <vtkOutputWindow.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace
{
const char* const Usage =
  "usage: bender-cli export IN_MESH -o OUT.stl|OUT.vtp|OUT.smesh|OUT.poly [options]\n"
  "\n"
  "Writes IN_MESH for CFD meshers. Coordinates are taken to be LPS millimetres (the frame of\n"
  "Bender's segmentations); every file states the frame and unit where its format allows\n"
  "(STL header, VTP field data, TetGen comment, the sidecar).\n"
  "\n"
  "options:\n"
  "  -o, --output OUT          the output (required; never the input); the format follows\n"
  "                            the extension: .stl; .vtp (keeps the patch labels\n"
  "                            CellEntityIds/ModelFaceID and their names); .smesh or .poly\n"
  "                            (TetGen: facet markers = CellEntityIds, wall 1, ends 2..,\n"
  "                            and a region point inside the lumen)\n"
  "  --cap                     close planar-ish open ends (vessel inlets/outlets) with flat\n"
  "                            labelled caps (wall = the rest); an error when there is\n"
  "                            nothing to cap (a closed surface without labelled ends)\n"
  "  --planarity F             a loop is capped when its points lie within F x its\n"
  "                            diameter of a plane (default 0.1)\n"
  "  --patches single|solids|files\n"
  "                            .stl only. single: one binary STL (default); solids: one\n"
  "                            ASCII STL with a solid per patch named by the patch (wall,\n"
  "                            inlet, outlet_1, ...; snappyHexMesh, gmsh, TetGen); files:\n"
  "                            one binary STL per patch, OUT_wall.stl, OUT_inlet.stl, ...\n"
  "                            whose rims share their vertices exactly\n"
  "  --unit mm|m               unit of the written coordinates (default mm; m divides by\n"
  "                            1000, as OpenFOAM expects)\n"
  "  --frame lps|ras           frame of the written coordinates (default lps; ras negates\n"
  "                            x and y)\n"
  "  --patches-json            also write OUT.patches.json (always written with --patches\n"
  "                            solids|files and for .smesh/.poly): per patch its name, id,\n"
  "                            type, centre, outward normal, area and equivalent diameter,\n"
  "                            a point inside the lumen, the unit and the frame\n"
  "  --quiet                   print nothing on success\n"
  "  -h, --help                this help\n"
  "\n"
  "Patches come from the cell array CellEntityIds with the names in the field data\n"
  "PatchNames (older files: PatchId), kept in .vtp files, or from --cap.\n"
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
  std::string outPath, patches = "single", frame = "lps", unit = "mm";
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
  cli.App.add_option("--unit", unit);
  cli.App.add_flag("--patches-json", options.patchesJson);
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
  if (unit == "mm" || unit == "m")
  {
    options.unit = unit;
  }
  else
  {
    return cli.UsageError("--unit: unknown value '" + unit + "' (expected mm or m)");
  }
  if (positional.size() != 1 || outPath.empty())
  {
    return cli.UsageError("expected IN_MESH -o OUT.stl");
  }
  std::string ext = std::filesystem::path(outPath).extension().string();
  for (char& c : ext)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  const std::optional<bender::MeshFormat> format = bender::FindMeshFormat(outPath);
  if (!format || !format->CanWrite())
  {
    std::fprintf(stderr,
      "bender-cli export: %s: the output must be %s\n",
      outPath.c_str(),
      bender::MeshExtensionList(bender::MeshAccess::Write).c_str());
    return 2;
  }
  if (ext != ".stl" && options.patches != bender::StlPatchMode::Single)
  {
    // .vtp and TetGen files keep every patch as labels in one file.
    std::fprintf(stderr,
      "bender-cli export: %s: --patches solids|files is for .stl; %s keeps the patches as "
      "labels\n",
      outPath.c_str(),
      ext.c_str());
    return 2;
  }
  if (options.patches != bender::StlPatchMode::Single)
  {
    options.stlEncoding = bender::StlEncoding::Ascii; // named solids are ASCII STL
  }
  // The sidecar goes with every export of patches.
  options.patchesJson =
    options.patchesJson || options.patches != bender::StlPatchMode::Single || format->regionPoint;
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
    if (result.patches.size() > 1)
    {
      std::string names;
      for (const bender::PatchLabel& patch : result.patches)
      {
        names += (names.empty() ? "" : ", ") + patch.name + " (" +
          bender::PatchTypeName(patch.type) + ", " + std::to_string(patch.id) + ")";
      }
      std::printf("patches: %s\n", names.c_str());
    }
    if (result.measured)
    {
      const auto& sidecar = result.sidecar;
      if (sidecar.hasInsidePoint)
      {
        std::printf("inside point: %.6g %.6g %.6g %s (%s)\n",
          sidecar.insidePoint[0],
          sidecar.insidePoint[1],
          sidecar.insidePoint[2],
          sidecar.unit.c_str(),
          bender::StlFrameName(sidecar.frame));
      }
      else
      {
        std::printf("no inside point: the surface is %s\n",
          sidecar.closed ? "closed but no point inside it was verified" : "not closed");
      }
    }
    std::printf("%lld triangles, %s%s\n",
      static_cast<long long>(report.triangles),
      report.closed ? "closed" : "open",
      report.closed ? (", volume " + std::to_string(std::abs(report.volume)) + " mm^3").c_str()
                    : "");
  }
  return 0;
}
