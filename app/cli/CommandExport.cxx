// bender-cli export IN -o OUT [--cap] [--patches single|solids|files] [--frame lps|ras]:
// CFD-ready STL of a vessel surface.

#include "CliCommands.h"

#include "BenderMeshCheck.h"
#include "BenderStlExport.h"
#include "MeshIO.h"
#include "vtkBenderCapFilter.h"

#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
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
  std::vector<std::string> positional;
  std::string outPath;
  bool cap = false, quiet = false;
  double planarity = 0.1;
  bender::StlExportOptions options;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& a = args[i];
    auto value = [&](std::string& out) {
      if (i + 1 >= args.size())
      {
        std::fprintf(stderr, "bender-cli export: %s needs a value\n", a.c_str());
        return false;
      }
      out = args[++i];
      return true;
    };
    std::string v;
    if (a == "-h" || a == "--help")
    {
      std::fputs(Usage, stdout);
      return 0;
    }
    else if (a == "-o" || a == "--output")
    {
      if (!value(outPath))
      {
        return 2;
      }
    }
    else if (a == "--cap")
    {
      cap = true;
    }
    else if (a == "--quiet")
    {
      quiet = true;
    }
    else if (a == "--planarity")
    {
      if (!value(v))
      {
        return 2;
      }
      char* end = nullptr;
      planarity = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end || !(planarity >= 0 && planarity <= 1))
      {
        std::fprintf(stderr, "bender-cli export: --planarity: '%s' is not in [0, 1]\n", v.c_str());
        return 2;
      }
    }
    else if (a == "--patches")
    {
      if (!value(v))
      {
        return 2;
      }
      if (v == "single")
      {
        options.patches = bender::StlPatchMode::Single;
      }
      else if (v == "solids")
      {
        options.patches = bender::StlPatchMode::Solids;
      }
      else if (v == "files")
      {
        options.patches = bender::StlPatchMode::Files;
      }
      else
      {
        std::fprintf(stderr, "bender-cli export: --patches: unknown value '%s'\n", v.c_str());
        return 2;
      }
    }
    else if (a == "--frame")
    {
      if (!value(v))
      {
        return 2;
      }
      if (v == "lps" || v == "LPS")
      {
        options.frame = bender::StlFrame::LPS;
      }
      else if (v == "ras" || v == "RAS")
      {
        options.frame = bender::StlFrame::RAS;
      }
      else
      {
        std::fprintf(stderr, "bender-cli export: --frame: unknown value '%s'\n", v.c_str());
        return 2;
      }
    }
    else if (a.size() > 1 && a[0] == '-')
    {
      std::fprintf(stderr, "bender-cli export: unknown option '%s'\n%s", a.c_str(), Usage);
      return 2;
    }
    else
    {
      positional.push_back(a);
    }
  }
  if (positional.size() != 1 || outPath.empty())
  {
    std::fprintf(stderr, "bender-cli export: expected IN_MESH -o OUT.stl\n%s", Usage);
    return 2;
  }
  const std::string& inPath = positional[0];
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
  if (cap)
  {
    vtkNew<vtkBenderCapFilter> capper;
    capper->SetInputData(mesh);
    capper->SetPlanarity(planarity);
    capper->Update();
    if (!capper->GetLastError().empty())
    {
      return Fail(inPath + ": " + capper->GetLastError());
    }
    if (!quiet)
    {
      std::printf("capped %d open end%s%s\n", capper->GetNumberOfCaps(),
        capper->GetNumberOfCaps() == 1 ? "" : "s",
        capper->GetNumberOfSkippedLoops()
          ? (", left " + std::to_string(capper->GetNumberOfSkippedLoops()) +
              " non-planar boundary loop(s) open")
              .c_str()
          : "");
    }
    mesh = capper->GetOutput();
  }
  std::vector<std::string> written;
  std::string ext = outPath.size() >= 4 ? outPath.substr(outPath.size() - 4) : "";
  for (char& c : ext)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  try
  {
    if (ext == ".stl")
    {
      // With one file per patch the names derive from OUT: none may be the input.
      for (const std::string& planned : bender::PlannedStlPaths(mesh, outPath, options))
      {
        if (bender::SameFile(inPath, planned))
        {
          return Fail(planned + ": refusing to overwrite the input file; choose another output");
        }
      }
      written = bender::ExportStl(mesh, outPath, options);
    }
    else if (ext == ".vtp")
    {
      // The VTK form keeps the PatchId cell labels (wall 0, caps 1..n), in LPS.
      if (options.frame != bender::StlFrame::LPS || options.patches != bender::StlPatchMode::Single)
      {
        std::fprintf(stderr, "bender-cli export: .vtp output is written whole, in LPS\n");
        return 2;
      }
      bender::MeshWriteOptions writeOptions;
      writeOptions.header = "bender export: frame LPS, unit mm";
      bender::WriteMesh(mesh, outPath, writeOptions);
      written.push_back(outPath);
    }
    else
    {
      std::fprintf(stderr, "bender-cli export: %s: the output must be .stl (or .vtp)\n",
        outPath.c_str());
      return 2;
    }
  }
  catch (const std::exception& e)
  {
    return Fail(e.what());
  }
  if (!quiet)
  {
    const auto report = bender::CheckMesh(mesh, nullptr, [] {
      bender::MeshCheckOptions o;
      o.selfIntersections = false;
      return o;
    }());
    for (const std::string& file : written)
    {
      std::printf("wrote %s\n", file.c_str());
    }
    std::printf("%lld triangles, %s%s\n", static_cast<long long>(report.triangles),
      report.closed ? "closed" : "open",
      report.closed ? (", volume " + std::to_string(std::abs(report.volume))).c_str() : "");
  }
  return 0;
}
