// bender-cli segment on a DICOM folder holding several series: as the window does, the largest
// is read and named in one line on stderr; --series UID reads the one asked for, and a UID the
// folder does not hold gets one line listing the series it does hold (exit 1, no output).
#include "DicomTestSeries.h"
#include "MeshIO.h"
#include "SegmentCommand.h"
#include "SegmentationTestUtilities.h"

#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>

namespace
{

const std::string Scout = "1.2.826.0.1.3680043.2.1125.9.1";
const std::string Angio = "1.2.826.0.1.3680043.2.1125.9.2";
const std::string Late = "1.2.826.0.1.3680043.2.1125.9.3";

// A folder with three series of CT_small.dcm copies: 2, 6 and 3 slices.
std::string WriteStudy(const bender_test::TempDir& dir)
{
  const std::string folder = dir.File("study");
  std::filesystem::create_directories(folder);
  const std::string slice = bender_test::ExternalData("CT_small.dcm");
  bender_test::WriteDicomTestSeries(folder, slice, Scout, "scout", 2);
  bender_test::WriteDicomTestSeries(folder, slice, Angio, "angio", 6);
  bender_test::WriteDicomTestSeries(folder, slice, Late, "late", 3);
  return folder;
}

// Whether the surface written spans `slices` slices of 2.5 mm along z: an all-lumen window
// keeps the volume's whole block, whose surface lies between the outer slices' centres
// ((n - 1) 2.5 mm apart) and a voxel beyond them; the series here differ by one slice or more.
void ExpectSlices(const std::string& surface, int slices)
{
  const vtkSmartPointer<vtkPolyData> mesh = bender::ReadMesh(surface);
  double b[6];
  mesh->GetBounds(b);
  EXPECT_GT(b[5] - b[4], (slices - 0.5) * 2.5) << surface;
  EXPECT_LT(b[5] - b[4], (slices + 1) * 2.5) << surface;
}

std::size_t Lines(const std::string& text)
{
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

} // namespace

TEST(SegmentDicomCli, SeveralSeriesTheLargestIsReadAndNamedOnStderr)
{
  bender_test::TempDir dir;
  const std::string folder = WriteStudy(dir);
  const std::string surface = dir.File("vessels.stl");
  std::ostringstream out, err;
  ASSERT_EQ(
    bender::RunSegmentCli({ folder, "-o", surface, "--lower", "-10000", "-q" }, out, err), 0)
    << err.str();
  ExpectSlices(surface, 6); // angio
  EXPECT_EQ(Lines(err.str()), 1u) << err.str();
  EXPECT_EQ(err.str().rfind("bender-cli segment: study: 3 DICOM series", 0), 0u) << err.str();
  EXPECT_NE(
    err.str().find("read the largest, \"angio\" (6 slices, UID " + Angio + ")"), std::string::npos)
    << err.str();
  EXPECT_NE(err.str().find("scout (2 slices)"), std::string::npos) << err.str();
  EXPECT_NE(err.str().find("late (3 slices)"), std::string::npos) << err.str();
}

TEST(SegmentDicomCli, SeriesChosenByUid)
{
  bender_test::TempDir dir;
  const std::string folder = WriteStudy(dir);

  // The one asked for, without a word about the choice.
  std::ostringstream out, err;
  ASSERT_EQ(bender::RunSegmentCli(
              { folder, "-o", dir.File("late.stl"), "--lower", "-10000", "--series", Late, "-q" },
              out,
              err),
    0)
    << err.str();
  EXPECT_TRUE(err.str().empty()) << err.str();
  ExpectSlices(dir.File("late.stl"), 3);

  // A UID the folder does not hold: one line naming the folder and the UID, listing the series.
  std::ostringstream out2, err2;
  EXPECT_EQ(bender::RunSegmentCli(
              { folder, "-o", dir.File("none.stl"), "--series", "1.2.3.4", "-q" }, out2, err2),
    1);
  const std::string message = err2.str();
  EXPECT_EQ(Lines(message), 1u) << message;
  EXPECT_NE(
    message.find(folder + ": no DICOM series with UID 1.2.3.4; the folder holds 3: [" + Scout +
      " \"scout\" 2 slices] [" + Angio + " \"angio\" 6 slices] [" + Late + " \"late\" 3 slices]"),
    std::string::npos)
    << message;
  EXPECT_FALSE(std::filesystem::exists(dir.File("none.stl")));
  EXPECT_TRUE(out2.str().empty()) << out2.str();
}
