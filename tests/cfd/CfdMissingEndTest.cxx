// A case never runs with a vessel end missing (issue 23): a tube with a side branch 1.2 mm
// wide, prepared for CFD (three ends), meshed with cells as large as the branch: snappyHexMesh
// leaves the branch's end without faces and the run stops after meshing, one line naming the
// end, where it is, how wide, and what to do. Needs OpenFOAM (label cfd).

#include "BenderErrors.h"
#include "CfdCase.h"
#include "CfdTestUtilities.h"
#include "PrepareForCfd.h"
#include "ThinBranchTube.h"

#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <string>

TEST(CfdMissingEnd, ARunStopsWhenTheMeshLosesAnEnd)
{
  BENDER_REQUIRE_PROGRAM("blockMesh");
  BENDER_REQUIRE_PROGRAM("snappyHexMesh");
  const bender::PrepareForCfdResult prepared = bender::test::PreparedThinBranchTube();
  ASSERT_EQ(prepared.ends.size(), 3u);
  std::string thin;
  for (const bender::CfdEnd& end : prepared.ends)
  {
    thin = end.radius < 1.0 ? end.name : thin;
  }
  ASSERT_FALSE(thin.empty());
  bender::test::TemporaryFolder folder("cfd-missing-end");
  bender::CfdCaseOptions options;
  options.caseDirectory = folder.Path() + "/case";
  options.cellSize = 1.2e-3; // as wide as the branch
  options.iterations = 5;
  bender::WriteOpenFoamCase({ prepared.surface, prepared.patches }, options);
  bender::CfdRunOptions run;
  run.steps = bender::CfdRunOptions::Steps::Mesh;
  try
  {
    bender::RunOpenFoamCase(options.caseDirectory, run);
    ADD_FAILURE() << "the mesh without " << thin << " was accepted";
  }
  catch (const bender::Error& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("snappyHexMesh left patch " + thin + " at ("), std::string::npos) << what;
    EXPECT_NE(what.find(" mm wide) without faces"), std::string::npos) << what;
    EXPECT_NE(what.find("--cell-size"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}
