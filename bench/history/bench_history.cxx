// bench_history: a long planning session (issue 25). The demo vessel
// (data/external/aneurysm_data.stl) in a BenderSession with the demo plan's first ribbon and
// parameters; 500 consecutive warps, each a grab, a swing of the ribbon's end by 3 degrees
// about its start (alternately one way and back, so that the vessel stays a vessel) and a
// release that commits (a commit the guard holds is kept, as the user can); every 10th warp is
// undone and redone. Then undo as far as the history allows, and redo everything.
// Printed: the commit time of the first and last 50 warps (median, p90, max), the history's
// bytes and the resident memory (VmRSS) every 50 warps, against the history's limit
// (WarpHistory::MemoryLimit, 1 GiB by default: the oldest steps' surfaces are let go beyond
// it), and how far undo reaches at the end.
//
// usage: bench_history [--warps N] [--limit-mib M] [--tiny]
//        (--tiny: 20 warps with a 64 MiB limit, for the ctest that proves it runs; no figure
//        is checked: WarpHistoryTest checks the memory bound)

#include "BenderSession.h"
#include "SwungRibbon.h"
#include "WarpHistory.h"
#include "WarpPlanIO.h"

#include "BenchMachine.h"

#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;
using bender_bench::Percentile;
using bender_bench::ResidentMiB;

double Ms(Clock::time_point since)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

std::string Figures(const std::vector<double>& ms)
{
  char text[128];
  std::snprintf(text,
    sizeof text,
    "median %.1f ms, p90 %.1f ms, max %.1f ms",
    Percentile(ms, 0.5),
    Percentile(ms, 0.9),
    Percentile(ms, 1.0));
  return text;
}

double MiB(std::size_t bytes)
{
  return double(bytes) / (1024.0 * 1024.0);
}
// The demo vessel in `session`, the demo plan's first ribbon placed and its parameters set.
bool Prepare(bender::BenderSession& session, std::size_t limit)
{
  const std::string vessel = std::string(BENDER_EXTERNAL_DATA_DIR) + "/aneurysm_data.stl";
  const bender::WarpPlan plan = bender::ReadWarpPlan(BENDER_DEMO_PLAN);
  if (plan.warps.empty() || !session.LoadSurface(vessel))
  {
    std::printf("the demo vessel or plan could not be used (%s)\n",
      session.GetMessages().empty() ? "no plan" : session.GetMessages().back().text.c_str());
    return false;
  }
  const bender::WarpSpec& demo = plan.warps.front();
  bender::WarpParameters parameters = session.GetParameters();
  parameters.radius = demo.radius;
  parameters.decay = demo.decay;
  session.SetParameters(parameters);
  session.SetHistoryMemoryLimit(limit);
  if (!session.PlaceRibbon(demo.initial))
  {
    std::printf("the demo ribbon could not be placed\n");
    return false;
  }
  return true;
}

// One warp: grab the ribbon where it is, swing its end by `degrees`, release (a commit the
// guard holds is kept). The milliseconds of the release, or a negative value when refused.
double Warp(bender::BenderSession& session, double degrees, int& held)
{
  const bender::RibbonSpec ribbon = *session.GetRibbon();
  if (!session.Grab(ribbon) || !session.MoveFinal(bendertest::Swung(ribbon, degrees)))
  {
    session.CancelGrab("benchmark: the move was refused");
    return -1.0;
  }
  const auto start = Clock::now();
  bool committed = session.Release();
  if (!committed && session.IsCommitHeld())
  {
    ++held;
    committed = session.KeepHeldCommit();
  }
  const double ms = Ms(start);
  if (!committed)
  {
    session.CancelGrab("benchmark: the commit failed");
    return -1.0;
  }
  return ms;
}

// 20 commits on a fresh session of the demo vessel.
std::vector<double> FreshCommits(std::size_t limit)
{
  bender::BenderSession session;
  std::vector<double> ms;
  int held = 0;
  if (Prepare(session, limit))
  {
    for (int k = 1; k <= 20; ++k)
    {
      const double t = Warp(session, k % 2 ? 3.0 : -3.0, held);
      if (t >= 0.0)
      {
        ms.push_back(t);
      }
    }
  }
  return ms;
}
} // namespace

int main(int argc, char** argv)
{
  int warps = 500;
  std::size_t limit = bender::WarpHistory::DefaultMemoryLimit;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--tiny"))
    {
      warps = 20;
      limit = std::size_t(64) << 20;
    }
    else if (!std::strcmp(argv[i], "--warps") && i + 1 < argc)
    {
      warps = std::max(1, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--limit-mib") && i + 1 < argc)
    {
      limit = std::size_t(std::max(0, std::atoi(argv[++i]))) << 20;
    }
    else
    {
      std::fprintf(stderr, "usage: bench_history [--warps N] [--limit-mib M] [--tiny]\n");
      return 2;
    }
  }
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  std::printf("bench_history, %s\n%s\n", date, bender_bench::MachineLine().c_str());

  bender::BenderSession session;
  if (!Prepare(session, limit))
  {
    return 1;
  }
  // The reference, in the same run: the same commits on a fresh session (another process's
  // load on the machine shows in both).
  const std::vector<double> referenceBefore = FreshCommits(limit);
  const std::size_t oneSurface = session.GetHistoryBytes();
  std::printf("demo vessel: %lld triangles, %.1f MiB per surface kept; history limit %.0f MiB; "
              "%d warps, every 10th undone and redone\n",
    (long long)session.GetSurface()->GetNumberOfPolys(),
    MiB(oneSurface),
    MiB(limit),
    warps);

  std::vector<double> commitMs, undoMs, redoMs;
  int held = 0, refused = 0;
  const auto report = [&](int done)
  {
    std::printf("%8d %14.1f %12.1f\n", done, MiB(session.GetHistoryBytes()), ResidentMiB());
    std::fflush(stdout);
  };
  std::printf("%8s %14s %12s\n", "warps", "history MiB", "VmRSS MiB");
  report(0);
  for (int k = 1; k <= warps; ++k)
  {
    const double ms = Warp(session, k % 2 ? 3.0 : -3.0, held);
    if (ms < 0.0)
    {
      ++refused;
      continue;
    }
    commitMs.push_back(ms);
    if (k % 10 == 0)
    {
      auto t = Clock::now();
      session.Undo();
      undoMs.push_back(Ms(t));
      t = Clock::now();
      session.Redo();
      redoMs.push_back(Ms(t));
    }
    if (k % 50 == 0 || k == warps)
    {
      report(k);
    }
  }
  const std::size_t position = session.GetHistoryPosition();
  std::size_t undone = 0;
  while (session.CanUndo() && session.Undo())
  {
    ++undone;
  }
  std::size_t redone = 0;
  while (session.CanRedo() && session.Redo())
  {
    ++redone;
  }
  const std::size_t first = std::min<std::size_t>(50, commitMs.size());
  const std::vector<double> head(commitMs.begin(), commitMs.begin() + first);
  const std::vector<double> tail(commitMs.end() - first, commitMs.end());
  std::printf("commits: %zu (%d held by the guard and kept, %d refused); plan: %zu steps\n",
    commitMs.size(),
    held,
    refused,
    position);
  std::printf("commit time, first %zu: %s\n", first, Figures(head).c_str());
  std::printf("commit time, last %zu:  %s\n", first, Figures(tail).c_str());
  const std::vector<double> referenceAfter = FreshCommits(limit);
  std::printf("reference, 20 commits on a fresh session before the soak: %s\n",
    Figures(referenceBefore).c_str());
  std::printf("reference, 20 commits on a fresh session after the soak:  %s\n",
    Figures(referenceAfter).c_str());
  std::printf("last %zu / first %zu (medians): %.2f; fresh after / before: %.2f\n",
    first,
    first,
    Percentile(tail, 0.5) / std::max(1e-9, Percentile(head, 0.5)),
    Percentile(referenceAfter, 0.5) / std::max(1e-9, Percentile(referenceBefore, 0.5)));
  std::printf("undo: %s; redo: %s\n", Figures(undoMs).c_str(), Figures(redoMs).c_str());
  std::printf("at the end: undo reaches back %zu of %zu steps, redo forward %zu; history %.1f "
              "MiB (limit %.0f MiB + the surfaces always kept), VmRSS %.1f MiB\n",
    undone,
    position,
    redone,
    MiB(session.GetHistoryBytes()),
    MiB(limit),
    ResidentMiB());
  return 0;
}
