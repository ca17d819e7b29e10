// bender-cli: the headless tool for batch work. Shares every module with the application.

#include "CliCommands.h"

#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <vector>

namespace
{
struct Command
{
  const char* name;
  const char* summary;
  int (*run)(const std::vector<std::string>&);
};

const Command Commands[] = {
  { "warp", "apply a warp plan (.bender.json) to a mesh", RunWarpCommand },
  { "segment", "segment the vessels of a volume and extract their surface", RunSegmentCommand },
  { "phantom", "build the MRA-like demo volume from a vessel surface", RunPhantomCommand },
  { "check", "check a mesh for CFD: watertight, manifold, flips, self-intersections",
    RunCheckCommand },
  { "export", "export a surface for CFD meshing (caps, patches, frame)", RunExportCommand },
  { "render", "render a mesh (optionally with a plan's ribbons) to a PNG", RunRenderCommand },
  { "tracker", "stream poses from a Polhemus Fastrak, a recording or the simulator",
    RunTrackerCommand },
};

void PrintHelp(std::FILE* out)
{
  std::fprintf(out,
    "usage: bender-cli COMMAND [ARGS...]\n"
    "       bender-cli COMMAND --help\n\n"
    "Bender: bend vessel surfaces with the ribbon warp, for surgery planning and CFD.\n\n"
    "commands:\n");
  for (const Command& c : Commands)
  {
    std::fprintf(out, "  %-10s %s\n", c.name, c.summary);
  }
}
} // namespace

int main(int argc, char** argv)
{
  if (argc < 2)
  {
    PrintHelp(stderr);
    return 2;
  }
  const std::string name = argv[1];
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
  for (const Command& c : Commands)
  {
    if (name == c.name)
    {
      // Commands report their own errors; this catches what escapes them (such as running out
      // of memory on an absurd parameter) so that the tool never aborts.
      try
      {
        return c.run(std::vector<std::string>(argv + 2, argv + argc));
      }
      catch (const std::bad_alloc&)
      {
        std::fprintf(stderr, "bender-cli %s: out of memory (check the parameters: a tolerance "
                             "or size too small or too large?)\n", c.name);
      }
      catch (const std::exception& e)
      {
        std::fprintf(stderr, "bender-cli %s: %s\n", c.name, e.what());
      }
      return 1;
    }
  }
  std::fprintf(stderr, "bender-cli: unknown command '%s' (see bender-cli --help)\n", name.c_str());
  return 2;
}
