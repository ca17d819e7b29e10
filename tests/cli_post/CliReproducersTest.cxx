// Issue 25's three file failures through bender-cli, as written in the issue: each now ends
// with one line on stderr naming the input and the problem, status 1, and nothing written.

#include "CliPostTestUtilities.h"
#include "HostileMeshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace
{
using clitest::Q;
namespace fs = std::filesystem;

class CliReproducers : public clitest::ScratchTest
{
protected:
  void Write(const std::string& name, const std::string& bytes) const
  {
    std::ofstream out(this->Tmp(name), std::ios::binary);
    out << bytes;
  }
  // One line, with a newline at its end.
  static void ExpectOneLine(const clitest::Result& r, const std::string& part)
  {
    EXPECT_EQ(r.status, 1) << r.errors;
    EXPECT_EQ(std::count(r.errors.begin(), r.errors.end(), '\n'), 1) << r.errors;
    EXPECT_NE(r.errors.find(part), std::string::npos) << r.errors;
  }
};
} // namespace

// Was: a segmentation fault in the cap's vtkDelaunay2D.
TEST_F(CliReproducers, CorruptedCubeCapFailsWithOneLine)
{
  this->Write("m.stl", bendertest::CorruptedCubeStl());
  const auto r = this->Run(
    "export " + Q(this->Tmp("m.stl")) + " -o " + Q(this->Tmp("o.stl")) + " --cap --patches solids");
  ExpectOneLine(r, "m.stl: capping failed: cannot cap the open end");
  EXPECT_EQ(this->Files(), std::vector<std::string>{ "m.stl" });
}

// Was: an STL with -inf and a patches.json volume of 1.1e+307 mm^3.
TEST_F(CliReproducers, CoordinateBeyondSinglePrecisionIsRefused)
{
  this->Write("m.off", bendertest::OpenTetrahedronOff("-1e308"));
  for (const std::string options : { "--cap --patches solids --frame ras", "--patches solids" })
  {
    const auto r =
      this->Run("export " + Q(this->Tmp("m.off")) + " -o " + Q(this->Tmp("o.stl")) + " " + options);
    ExpectOneLine(r, "m.off: line 4: coordinate -1e+308 is beyond the single-precision range");
    EXPECT_EQ(this->Files(), std::vector<std::string>{ "m.off" }) << options;
  }
}

// Was: 13 lines (VTK's logger echoing the filter's error and the executive's request dump).
TEST_F(CliReproducers, TinySubdivisionToleranceFailsWithOneLine)
{
  this->Write("plane.stl", bendertest::CubeStl(4));
  this->Write("tiny.bender.json", R"({
  "format": "bender-warps", "version": 1, "units": "model",
  "warps": [ {
    "initial": {
      "start": { "position": [-0.35, 0, 0], "tangent": [1, 0, 0], "normal": [0, 1, 0] },
      "end": { "position": [0.35, 0, 0], "tangent": [1, 0, 0], "normal": [0, 1, 0] } },
    "final": {
      "start": { "position": [-0.35, 0.3, 0], "tangent": [1, 0, 0], "normal": [0, 1, 0] },
      "end": { "position": [0.35, 0.3, 0], "tangent": [1, 0, 0], "normal": [0, 1, 0] } },
    "radius": 0.16, "decay": { "shape": "bell" },
    "subdivision": { "tolerance": 1e-12, "maxPasses": 64 } } ] })");
  const auto r = this->Run("warp " + Q(this->Tmp("plane.stl")) + " " +
    Q(this->Tmp("tiny.bender.json")) + " " + Q(this->Tmp("w.stl")));
  ExpectOneLine(r, "tiny.bender.json: warps[0]: subdivision: subdivision tolerance 1e-12");
  EXPECT_FALSE(fs::exists(this->Tmp("w.stl")));
}
