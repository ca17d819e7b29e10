// bender_fault_driver: the operations of the crash-safety tests (CrashSafetyTest.cxx) that
// bender-cli has no command for, run in a process of their own so that BENDER_FAULT_AT can kill
// it (FaultInjection.h). After each step it prints one line and flushes, so the test knows what
// was complete when the process died.
//   session MESH PLAN AUTOSAVE   loads MESH with autosave on, applies PLAN's warps one by one
//                                ("applied K" after the K-th, its autosave written)
//   record FILE CHUNKS           records CHUNKS chunks ("appended K"): chunk K is K + 1
//                                repeated 100 + K times, received at K / 100 s

#include "BenderSession.h"
#include "StreamRecorder.h"
#include "WarpPlanIO.h"

#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

int main(int argc, char** argv)
{
  const std::vector<std::string> args(argv + 1, argv + argc);
  try
  {
    if (args.size() == 4 && args[0] == "session")
    {
      bender::BenderSession session;
      session.SetAutosavePath(args[3]);
      if (!session.LoadSurface(args[1]))
      {
        std::fprintf(stderr, "cannot load %s\n", args[1].c_str());
        return 1;
      }
      const bender::WarpPlan plan = bender::ReadWarpPlan(args[2]);
      for (std::size_t k = 0; k < plan.warps.size(); ++k)
      {
        if (!session.ApplyWarp(plan.warps[k]))
        {
          std::fprintf(stderr, "warp %zu failed\n", k + 1);
          return 1;
        }
        std::printf("applied %zu\n", k + 1);
        std::fflush(stdout);
      }
      return 0;
    }
    if (args.size() == 3 && args[0] == "record")
    {
      bender::StreamRecorder recorder(args[1]);
      const int chunks = std::stoi(args[2]);
      for (int k = 0; k < chunks; ++k)
      {
        const std::vector<std::uint8_t> chunk(
          static_cast<std::size_t>(100 + k), static_cast<std::uint8_t>(k + 1));
        recorder.Append(chunk.data(), chunk.size(), k / 100.0);
        std::printf("appended %d\n", k + 1);
        std::fflush(stdout);
      }
      recorder.Close();
      return 0;
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  std::fprintf(
    stderr, "usage: bender_fault_driver session MESH PLAN AUTOSAVE | record FILE CHUNKS\n");
  return 2;
}
