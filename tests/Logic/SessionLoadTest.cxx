// The session's mesh loading as a job (read off the session's thread, committed on it) and the
// autosave of a ribbon that changed no warp.
#include "BenderSession.h"
#include "LogicTestUtilities.h"
#include "MeshIO.h"
#include "SessionAutosave.h"

#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <thread>

using namespace bender;
namespace test = bender::test;

TEST(SessionLoad, TheJobReadsOnAnotherThreadAndTheSessionTakesTheSurfaceAtFinish)
{
  const std::string folder = test::TemporaryFolder("session-load");
  const vtkSmartPointer<vtkPolyData> tube = test::MakeTube(0, 60, 3);
  WriteMesh(tube, folder + "/tube.vtp");
  BenderSession session;
  auto job = session.BeginLoadSurface(folder + "/tube.vtp");
  ASSERT_TRUE(job);
  EXPECT_EQ(job->GetKind(), SessionJob::Kind::Load);
  // Busy until finished: nothing else changes the session meanwhile.
  EXPECT_TRUE(session.IsBusy());
  EXPECT_FALSE(session.BeginLoadSurface(folder + "/tube.vtp"));
  EXPECT_FALSE(session.HasSurface());
  std::thread worker([job]() { job->Run({}); });
  worker.join();
  EXPECT_FALSE(session.HasSurface()) << "nothing is taken before Finish";
  ASSERT_TRUE(session.Finish(*job));
  EXPECT_FALSE(session.IsBusy());
  ASSERT_TRUE(session.HasSurface());
  EXPECT_EQ(test::MaxDifference(session.GetSurface(), tube), 0.0);
  EXPECT_EQ(session.GetSurfaceName(), "tube.vtp");
  EXPECT_TRUE(std::filesystem::path(session.GetSourcePath()).is_absolute());
  EXPECT_TRUE(std::filesystem::equivalent(session.GetSourcePath(), folder + "/tube.vtp"));

  // LoadSurface is the same job at once; a file that cannot be read leaves the surface as it
  // was, with one message naming the file.
  std::ofstream(folder + "/broken.stl") << "solid broken\nfacet normal 0 0 1\n";
  EXPECT_FALSE(session.LoadSurface(folder + "/broken.stl"));
  const auto& said = session.GetMessages();
  ASSERT_FALSE(said.empty());
  EXPECT_EQ(said.back().severity, MessageSeverity::Error);
  EXPECT_NE(said.back().text.find("broken.stl"), std::string::npos) << said.back().text;
  EXPECT_FALSE(session.IsBusy());
  EXPECT_EQ(test::MaxDifference(session.GetSurface(), tube), 0.0);
  EXPECT_EQ(session.GetSurfaceName(), "tube.vtp");
}

TEST(SessionLoad, APlacedRibbonIsAutosavedOnceWhenAsked)
{
  const std::string folder = test::TemporaryFolder("session-ribbon-autosave");
  const std::string autosave = folder + "/autosave.bender-session.json";
  BenderSession session;
  const RibbonSpec placed = test::StraightRibbon(20, 40);
  // No autosave path: nothing to keep.
  ASSERT_TRUE(session.SetSurface(test::MakeTube(0, 60, 3), "tube"));
  ASSERT_TRUE(session.PlaceRibbon(placed));
  EXPECT_FALSE(session.HasUnsavedRibbon());

  session.SetAutosavePath(autosave);
  EXPECT_TRUE(session.HasUnsavedRibbon());
  // The decorator adds the ribbon, as the window's does.
  session.SetAutosaveDecorator(
    [&session](SessionSnapshot& snapshot)
    {
      if (session.GetRibbon())
      {
        snapshot.ribbon = SessionRibbon{};
        snapshot.ribbon->ribbon = *session.GetRibbon();
      }
    });
  ASSERT_TRUE(session.AutosaveRibbon());
  EXPECT_FALSE(session.HasUnsavedRibbon());
  const SessionSnapshot kept = ReadSessionFile(autosave);
  ASSERT_TRUE(kept.ribbon);
  EXPECT_EQ(kept.ribbon->ribbon.end.position.x, placed.end.position.x);

  // Moved: unsaved again; grabbed: the release's own autosave keeps it.
  const RibbonSpec moved = test::Bent(placed, 10.0);
  ASSERT_TRUE(session.PlaceRibbon(moved));
  EXPECT_TRUE(session.HasUnsavedRibbon());
  ASSERT_TRUE(session.Grab(moved));
  EXPECT_FALSE(session.HasUnsavedRibbon());
  session.CancelGrab("test");
  EXPECT_TRUE(session.HasUnsavedRibbon());
  // Any autosave keeps the ribbon lying on the surface.
  ASSERT_TRUE(session.Autosave());
  EXPECT_FALSE(session.HasUnsavedRibbon());
  // Discarded: the next autosave must keep it again.
  session.DiscardAutosave();
  EXPECT_TRUE(session.HasUnsavedRibbon());
  session.SetAutosaveDecorator(nullptr);
}
