// A DICOM series chosen by its folder (issue 12): the window's read job takes a folder; with
// several series it reads the largest and says which (and what else is there), a chosen UID is
// read as asked, a folder with no DICOM gets one clear line naming it; the loaded volume
// remembers its folder and series (what the autosave keeps).
#include "SegmentationSession.h"

#include "BenderErrors.h"
#include "DicomTestSeries.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

using namespace bender;

namespace
{

struct TempFolder
{
  std::filesystem::path path;
  explicit TempFolder(const std::string& name)
  {
    std::random_device random;
    this->path = std::filesystem::temp_directory_path() /
      ("bender-dicom-" + std::to_string(random()) + "-" + std::to_string(random())) / name;
    std::filesystem::create_directories(this->path);
  }
  ~TempFolder()
  {
    std::error_code ec;
    std::filesystem::remove_all(this->path.parent_path(), ec);
  }
};

std::string CtSlice()
{
  const std::string path = std::string(BENDER_EXTERNAL_DATA_DIR) + "/CT_small.dcm";
  if (!std::filesystem::exists(path))
  {
    ADD_FAILURE() << "missing test data " << path << ": run scripts/fetch-data";
  }
  return path;
}

const std::string Small = "1.2.826.0.1.3680043.2.1125.7.1";
const std::string Large = "1.2.826.0.1.3680043.2.1125.7.2";
const std::string Medium = "1.2.826.0.1.3680043.2.1125.7.3";

}

TEST(DicomFolder, OneSeriesIsReadWithoutANote)
{
  TempFolder folder("head");
  bender_test::WriteDicomTestSeries(folder.path.string(), CtSlice(), Small, "axial", 4);
  SegmentationSession session;
  auto job = session.BeginRead(folder.path.string() + "/");
  job->Run({});
  ASSERT_TRUE(job->volume);
  EXPECT_EQ(job->volume->geometry.size[2], 4u);
  EXPECT_NEAR(job->volume->geometry.spacing[2], 2.5, 1e-3);
  EXPECT_TRUE(job->note.empty()) << job->note;
  EXPECT_TRUE(job->seriesRead.empty());
  session.FinishRead(*job);
  EXPECT_EQ(session.GetVolumeName(), "head");
  EXPECT_EQ(std::filesystem::path(session.GetVolumeSource().path).filename(), "head");
  EXPECT_TRUE(std::filesystem::path(session.GetVolumeSource().path).is_absolute());
  EXPECT_TRUE(session.GetVolumeSource().dicomSeriesUid.empty());
}

TEST(DicomFolder, SeveralSeriesTheLargestIsReadAndTheUserIsTold)
{
  TempFolder folder("study");
  const std::string path = folder.path.string();
  bender_test::WriteDicomTestSeries(path, CtSlice(), Small, "scout", 2);
  bender_test::WriteDicomTestSeries(path, CtSlice(), Large, "angio", 6);
  bender_test::WriteDicomTestSeries(path, CtSlice(), Medium, "late", 3);
  SegmentationSession session;
  auto job = session.BeginRead(path + "/");
  job->Run({});
  ASSERT_TRUE(job->volume);
  EXPECT_EQ(job->volume->geometry.size[2], 6u);
  EXPECT_EQ(job->seriesRead, Large);
  EXPECT_NE(job->note.find("study: 3 DICOM series"), std::string::npos) << job->note;
  EXPECT_NE(
    job->note.find("read the largest, \"angio\" (6 slices, UID " + Large + ")"), std::string::npos)
    << job->note;
  EXPECT_NE(job->note.find("scout (2 slices)"), std::string::npos) << job->note;
  EXPECT_NE(job->note.find("late (3 slices)"), std::string::npos) << job->note;
  EXPECT_EQ(job->note.find('\n'), std::string::npos);
  session.FinishRead(*job);
  EXPECT_EQ(session.GetVolumeSource().dicomSeriesUid, Large);

  // The choice alone (for other readers of folders): the same series and sentence; nothing
  // to choose for a file.
  std::string note;
  EXPECT_EQ(ChooseLargestDicomSeries(path, note), Large);
  EXPECT_EQ(note, job->note);
  EXPECT_EQ(ChooseLargestDicomSeries(path + "/angio_0.dcm", note), "");
  EXPECT_TRUE(note.empty());

  // A series asked for by UID (a recovered session's): that one, nothing to say.
  auto chosen = session.BeginRead(path, Medium);
  chosen->Run({});
  EXPECT_EQ(chosen->volume->geometry.size[2], 3u);
  EXPECT_EQ(chosen->seriesRead, Medium);
  EXPECT_TRUE(chosen->note.empty());
}

TEST(DicomFolder, AFolderWithoutDicomGetsOneClearLine)
{
  TempFolder folder("notes");
  std::ofstream(folder.path / "readme.txt") << "not a DICOM file\n";
  SegmentationSession session;
  auto job = session.BeginRead(folder.path.string());
  try
  {
    job->Run({});
    FAIL() << "a folder without DICOM was read";
  }
  catch (const bender::Error& e)
  {
    const std::string message = e.what();
    EXPECT_NE(message.find("notes"), std::string::npos) << message;
    EXPECT_NE(message.find("no DICOM series"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_FALSE(job->volume);
  EXPECT_FALSE(session.HasVolume());
}

// The one choice of the window and of bender-cli segment: a UID asked for is checked against
// the folder, and one it does not hold gets one line listing what it does hold.
TEST(DicomFolder, ChooseDicomSeriesChecksTheUidAskedFor)
{
  TempFolder folder("study");
  const std::string path = folder.path.string();
  bender_test::WriteDicomTestSeries(path, CtSlice(), Small, "scout", 2);
  bender_test::WriteDicomTestSeries(path, CtSlice(), Large, "angio", 5);
  std::string note = "stale";
  EXPECT_EQ(ChooseDicomSeries(path, Small, note), Small);
  EXPECT_TRUE(note.empty()) << note;
  EXPECT_EQ(ChooseDicomSeries(path, "", note), Large);
  EXPECT_NE(note.find("read the largest, \"angio\" (5 slices"), std::string::npos) << note;
  // A file: nothing to check here (ReadVolume says what is wrong with it).
  EXPECT_EQ(ChooseDicomSeries(path + "/scout_0.dcm", Medium, note), Medium);
  EXPECT_TRUE(note.empty()) << note;

  const std::string unknown = "1.2.3.999";
  for (const std::string& asked : { unknown, Medium })
  {
    try
    {
      ChooseDicomSeries(path, asked, note);
      FAIL() << "a UID the folder does not hold was accepted: " << asked;
    }
    catch (const bender::Error& e)
    {
      const std::string message = e.what();
      EXPECT_NE(message.find(path + ": no DICOM series with UID " + asked), std::string::npos)
        << message;
      EXPECT_NE(message.find("the folder holds 2: [" + Small + " \"scout\" 2 slices] [" + Large +
                  " \"angio\" 5 slices]"),
        std::string::npos)
        << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }

  // The window's read job asks the same question: a recovered session whose series is gone.
  SegmentationSession session;
  auto job = session.BeginRead(path, unknown);
  EXPECT_THROW(job->Run({}), bender::Error);
  EXPECT_FALSE(job->volume);
}
