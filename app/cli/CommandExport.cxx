// bender-cli export IN -o OUT [--cap] [--patches single|solids|files] [--frame lps|ras]
// [--unit mm|m] [--patches-json]: CFD-ready surfaces for meshers (STL, VTP, TetGen).

#include "CliCommand.h"
#include "CliParsing.h"

#include "ExportSurface.h"
#include "MeshFormats.h"
#include "StringUtil.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

namespace
{
const char* const Details =
  "Writes IN_MESH for CFD meshers. Coordinates are taken to be LPS millimetres (the frame of "
  "Bender's segmentations); every file states the frame and unit where its format allows (STL "
  "header, VTP field data, TetGen comment, the sidecar).\n"
  "\n"
  "The format follows the extension of OUT (every writable format of `bender-cli formats`): "
  ".stl (patches as named solids or files); .vtp (keeps the patch labels "
  "CellEntityIds/ModelFaceID and their names); .smesh or .poly (TetGen: facet markers = "
  "CellEntityIds, wall 1, ends 2.., and a region point inside the lumen).\n"
  "Patches come from the cell array CellEntityIds with the names in the field data PatchNames "
  "(older files: PatchId), kept in .vtp files, or from --cap.\n"
  "\n"
  "example: bender-cli export vessel-cfd.vtp -o vessel-cfd.stl --patches solids --unit m\n"
  "\n"
  "exit status: 0 written, 1 bad input or write failure, 2 usage error";

struct ExportArguments
{
  std::string input;
  bender::ExportSurfaceOptions options;
  std::string patches = "single";
  std::string frame = "lps";
  bool quiet = false;
};

void PrintResult(const bender::ExportSurfaceOptions& options,
  const bender::ExportSurfaceResult& result)
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
      names += (names.empty() ? "" : ", ") + patch.name + " (" + bender::PatchTypeName(patch.type) +
        ", " + std::to_string(patch.id) + ")";
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
    report.closed ? (", volume " + std::to_string(std::abs(report.volume)) + " mm^3").c_str() : "");
}

int RunExport(ExportArguments a)
{
  bender::ExportSurfaceOptions& options = a.options;
  const std::string& outPath = options.output;
  const std::optional<bender::MeshFormat> format = bender::FindMeshFormat(outPath);
  if (!format || !format->CanWrite())
  {
    return bender::UsageError(std::cerr,
      "export",
      outPath + ": the output must be " + bender::MeshExtensionList(bender::MeshAccess::Write));
  }
  options.patches = a.patches == "solids" ? bender::StlPatchMode::Solids
    : a.patches == "files"                ? bender::StlPatchMode::Files
                                          : bender::StlPatchMode::Single;
  options.frame = a.frame == "ras" ? bender::StlFrame::RAS : bender::StlFrame::LPS;
  // The format's rules: where patches can be named, and the sidecar with every export of
  // patches unless --patches-json asks for it anyway.
  bender::MeshExportRequest request;
  request.patches = options.patches;
  request.sidecar = options.patchesJson ? bender::SidecarChoice::On : bender::SidecarChoice::Auto;
  const bender::MeshExportRules rules = bender::ResolveMeshExport(*format, request);
  if (!rules.problem.empty())
  {
    return bender::UsageError(std::cerr, "export", outPath + ": " + rules.problem);
  }
  options.patchesJson = rules.sidecar;
  options.protectedPath = a.input;
  options.sourceName = bender::DisplayName(a.input);
  if (bender::SameFile(a.input, outPath))
  {
    return bender::CommandError(
      "export", outPath + ": refusing to overwrite the input file; choose another output");
  }
  const vtkSmartPointer<vtkPolyData> mesh = bender::ReadMesh(a.input);
  const bender::ExportSurfaceResult result = bender::ExportSurface(mesh, options);
  if (!a.quiet)
  {
    PrintResult(options, result);
  }
  return 0;
}
} // namespace

void bender::AddExportCommand(CLI::App& cli)
{
  auto a = std::make_shared<ExportArguments>();
  CLI::App* e = AddCommand(cli,
    "export",
    "export a surface for CFD meshing (caps, patches, frame)",
    Details,
    [a] { return RunExport(*a); });
  ExportSurfaceOptions& options = a->options;
  e->add_option("IN_MESH", a->input, "the surface to export")->required();
  e->add_option("-o,--output",
     options.output,
     "the output (never the input); the format follows the extension: " +
       MeshExtensionList(MeshAccess::Write, " ") + " (bender-cli formats)")
    ->required()
    ->type_name("OUT");
  e->add_flag("--cap",
    options.cap,
    "close planar-ish open ends (vessel inlets/outlets) with flat labelled caps (wall = the "
    "rest); an error when there is nothing to cap (a closed surface without labelled ends)");
  e->add_option("--planarity",
     options.planarity,
     "a loop is capped when its points lie within F x its diameter of a plane, in [0, 1]")
    ->type_name("F")
    ->check(NumberIn(0.0, 1.0))
    ->capture_default_str();
  std::string named;
  for (const MeshFormat& format : MeshFormats())
  {
    if (format.namedPatches && format.CanWrite())
    {
      named += (named.empty() ? "" : " ") + format.extensions.front();
    }
  }
  OneOf(e->add_option("--patches",
          a->patches,
          "for formats that name their patches (" + named +
            "). single: one file; solids: one ASCII STL with a solid per patch named by the "
            "patch (wall, inlet, outlet_1, ...; snappyHexMesh, gmsh, TetGen); files: one "
            "binary STL per patch, OUT_wall.stl, OUT_inlet.stl, ... whose rims share their "
            "vertices exactly"),
    { "single", "solids", "files" })
    ->capture_default_str();
  OneOf(e->add_option("--unit",
          options.unit,
          "unit of the written coordinates (m divides by 1000, as OpenFOAM expects)"),
    { "mm", "m" })
    ->capture_default_str();
  OneOf(
    e->add_option("--frame", a->frame, "frame of the written coordinates (ras negates x and y)"),
    { "lps", "ras" })
    ->capture_default_str();
  e->add_flag("--patches-json",
    options.patchesJson,
    "also write OUT.patches.json (always written with --patches solids|files and for "
    ".smesh/.poly): per patch its name, id, type, centre, outward normal, area and equivalent "
    "diameter, a point inside the lumen, the unit and the frame");
  e->add_flag("--quiet", a->quiet, "print nothing on success");
}
