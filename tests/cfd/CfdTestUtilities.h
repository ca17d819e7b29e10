#ifndef bender_CfdTestUtilities_h
#define bender_CfdTestUtilities_h

// Shared by the CFD case tests: the real surfaces (the gmsh aneurysm capped with labelled ends,
// original and bent by the demo plan), fresh folders and running external programs.

#include "CfdCase.h"
#include "ProcessRunner.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <string>

namespace bender::test
{

/// data/external/aneurysm_data.stl (open at its three ends), bent by data/demo/demo.bender.json
/// when `bent`, capped by vtkBenderCapFilter: closed, ends labelled inlet, outlet_1, outlet_2
/// (PatchLabels.h). LPS mm.
vtkSmartPointer<vtkPolyData> CappedAneurysm(bool bent);

/// The segmented demo vessel (SegmentDemoVessel: the MRA-like phantom of the aneurysm,
/// segmented; a closed blob), bent by the demo plan when `bent`, then made CFD-ready by
/// PrepareForCfd (ends clipped perpendicular to the centerlines, flow extensions, labelled
/// caps), as the demo job does. Computed once per process and bend. LPS mm.
vtkSmartPointer<vtkPolyData> PreparedDemoVessel(bool bent);

/// A straight tube along +x from x = 0 to `length` of radius `radius` (mm), `rings` rings of
/// `sides` points (the one tube generator's wall: SweepOpenTube, CfdVerificationTubes.h), capped
/// by vtkBenderCapFilter: closed, the end at x = 0 labelled inlet, the
/// other outlet_1 (PatchLabels.h). LPS mm.
vtkSmartPointer<vtkPolyData> CappedTube(double length, double radius, int rings, int sides);

/// A new empty folder under the system's temporary folder, removed by the destructor.
class TemporaryFolder
{
public:
  explicit TemporaryFolder(const std::string& tag);
  ~TemporaryFolder();
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  const std::string& Path() const { return this->Folder; }

private:
  std::string Folder;
};

/// Runs `command` with sh in `folder` (stdin from /dev/null), returning stdout and stderr
/// together; status is the exit status (-1 when it could not run or was killed).
std::string RunIn(const std::string& folder, const std::string& command, int& status);

/// The whole text of a file ("" when unreadable).
std::string ReadText(const std::string& path);

} // namespace bender::test

/// Skips the test when `program` is not installed, unless BENDER_REQUIRE_CFD is set in the
/// environment (CI after scripts/setup): then a missing program fails the test.
#define BENDER_REQUIRE_PROGRAM(program)                                                            \
  do                                                                                               \
  {                                                                                                \
    if (bender::FindExecutable(program).empty())                                                   \
    {                                                                                              \
      if (std::getenv("BENDER_REQUIRE_CFD"))                                                       \
      {                                                                                            \
        FAIL() << program                                                                          \
               << " is not installed but BENDER_REQUIRE_CFD is set (scripts/setup "                \
                  "installs openfoam, tetgen and gmsh)";                                           \
      }                                                                                            \
      GTEST_SKIP() << program << " is not installed (scripts/setup installs it)";                  \
    }                                                                                              \
  } while (false)

#endif
