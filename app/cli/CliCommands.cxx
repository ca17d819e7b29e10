// The bender-cli command table and dispatch (main.cxx only forwards argv here).

#include "CliCommands.h"

#include "DataDirectory.h"

#include <filesystem>

#include <cstdio>
#include <exception>
#include <new>

namespace bender
{

const std::vector<CliCommand>& CliCommandTable()
{
  static const std::vector<CliCommand> commands = {
    { "warp", "apply a warp plan (.bender.json) to a mesh", RunWarpCommand },
    { "segment", "segment the vessels of a volume and extract their surface", RunSegmentCommand },
    { "phantom", "build the MRA-like demo volume from a vessel surface", RunPhantomCommand },
    { "check",
      "check a mesh for CFD: watertight, manifold, flips, self-intersections",
      RunCheckCommand },
    { "export", "export a surface for CFD meshing (caps, patches, frame)", RunExportCommand },
    { "render", "render a mesh (optionally with a plan's ribbons) to a PNG", RunRenderCommand },
    { "centerline", "vessel centerlines with the inscribed-sphere radius", RunCenterlineCommand },
    { "measure", "per-branch vessel measures, before and after a warp", RunMeasureCommand },
    { "clip",
      "clip vessel ends for CFD: perpendicular cuts, flow extensions, labelled caps",
      RunClipCommand },
    { "cfd-case", "an OpenFOAM case of a labelled vessel (and its run)", RunCfdCaseCommand },
    { "tracker",
      "stream poses from a Polhemus Fastrak, OpenIGTLink, a recording or the simulator",
      RunTrackerCommand },
    { "igtl-send", "send a surface to 3D Slicer (OpenIGTLink POLYDATA, RAS)", RunIgtlSendCommand },
  };
  return commands;
}

namespace
{
void PrintHelp(std::FILE* out)
{
  std::fprintf(out,
    "usage: bender-cli COMMAND [ARGS...]\n"
    "       bender-cli COMMAND --help\n"
    "       bender-cli --version | --data-dir\n\n"
    "Bender: bend vessel surfaces with the ribbon warp, for surgery planning and CFD.\n\n"
    "commands:\n");
  for (const CliCommand& c : CliCommandTable())
  {
    std::fprintf(out, "  %-10s %s\n", c.name, c.summary);
  }
}
} // namespace

int RunBenderCli(const std::vector<std::string>& args)
{
  if (args.empty())
  {
    PrintHelp(stderr);
    return 2;
  }
  const std::string& name = args[0];
  if (name == "--help" || name == "-h" || name == "help")
  {
    PrintHelp(stdout);
    return 0;
  }
  if (name == "--version")
  {
    std::printf("bender-cli 0.1.0\n");
    return 0;
  }
  if (name == "--data-dir")
  {
    // Where the demo data is looked for (BENDER_DATA_DIR, else <bin>/../share/bender).
    const std::string dir = DataDirectory();
    std::error_code error;
    if (!std::filesystem::is_directory(std::filesystem::path(dir) / "demo", error))
    {
      std::fprintf(stderr,
        "bender-cli: %s: no Bender data folder (demo/ missing); install Bender or set "
        "BENDER_DATA_DIR\n",
        dir.c_str());
      return 1;
    }
    std::printf("%s\n", dir.c_str());
    return 0;
  }
  for (const CliCommand& c : CliCommandTable())
  {
    if (name == c.name)
    {
      // Commands report their own errors; this catches what escapes them (such as running out
      // of memory on an absurd parameter) so that the tool never aborts.
      try
      {
        return c.run(std::vector<std::string>(args.begin() + 1, args.end()));
      }
      catch (const std::bad_alloc&)
      {
        std::fprintf(stderr,
          "bender-cli %s: out of memory (check the parameters: a tolerance or size too small or "
          "too large?)\n",
          c.name);
      }
      catch (const std::exception& e)
      {
        std::fprintf(stderr, "bender-cli %s: %s\n", c.name, e.what());
      }
      std::fflush(stdout);
      return 1;
    }
  }
  std::fprintf(stderr, "bender-cli: unknown command '%s' (see bender-cli --help)\n", name.c_str());
  return 2;
}

} // namespace bender
