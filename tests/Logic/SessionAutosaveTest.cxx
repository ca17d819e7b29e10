// The autosave snapshot (issue 12, "no lost work"): every field written and read back exactly
// (surface, name, plan, volume and its identity, every segmentation parameter, the ribbon and
// its Bend parameters), version 1 files still read, corrupt and out-of-range files refused
// with one line naming the file and the field, nothing written for a snapshot that cannot be.
#include "SessionAutosave.h"

#include "VolumeIO.h"
#include "WarpPlanIO.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <thread>

using namespace bender;

namespace
{

struct TempFolder
{
  std::filesystem::path path;
  TempFolder()
  {
    std::random_device random;
    this->path = std::filesystem::temp_directory_path() /
      ("bender-session-file-" + std::to_string(random()) + "-" + std::to_string(random()));
    std::filesystem::create_directories(this->path);
  }
  ~TempFolder()
  {
    std::error_code ec;
    std::filesystem::remove_all(this->path, ec);
  }
  std::string File(const std::string& name) const { return (this->path / name).string(); }
};

std::string ReadText(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

void WriteText(const std::string& path, const std::string& text)
{
  std::ofstream out(path, std::ios::binary);
  out << text;
}

RibbonSpec Ribbon(double x0, double x1)
{
  RibbonSpec ribbon;
  ribbon.start.position = { x0, 0.25, -1.5 };
  ribbon.start.tangent = { 1, 0, 0 };
  ribbon.start.normal = { 0, 0, 1 };
  ribbon.end.position = { x1, 0.75, -1.0 / 3.0 };
  ribbon.end.tangent = { std::sqrt(0.5), std::sqrt(0.5), 0 };
  ribbon.end.normal = { 0, 0, 1 };
  return ribbon;
}

// A snapshot whose every field differs from its default (values that do not print short, so a
// rounding on the way would show).
SessionSnapshot FullSnapshot()
{
  SessionSnapshot s;
  s.sourcePath = "/data/patient 7/vessel.vtp";
  s.surfaceName = "segmented vessel";
  s.frame = "LPS";
  WarpSpec warp;
  warp.initial = Ribbon(10.0, 30.0);
  warp.final = Ribbon(10.0, 28.0 + 1.0 / 7.0);
  warp.radius = 12.345678901234567;
  warp.decay.shape = DecayShape::Plateau;
  warp.decay.plateau = 0.4;
  s.plan.warps = { warp, warp };
  s.plan.warps[1].radius = 7.5;

  SessionVolume volume;
  volume.path = "/data/patient 7/dicom";
  volume.name = "dicom";
  volume.dicomSeriesUid = "1.2.826.0.1.3680043.2.1125.1.2";
  volume.geometry.size = { 256, 240, 131 };
  volume.geometry.spacing = { 0.9375, 0.9375, 1.0 / 3.0 };
  volume.geometry.origin = { -120.3, 98.7, 1e-7 };
  volume.geometry.direction = { 0, 1, 0, -1, 0, 0, 0, 0, 1 };
  volume.maskPath = "/home/u/.local/share/Bender/autosave.bender-session.json.mask.nrrd";
  s.volume = volume;

  SegmentationSettings settings;
  SegmentationParameters& p = settings.segmentation;
  p.method = SegmentationMethod::Vesselness;
  p.lower = 187.25;
  p.upper = 1999.5;
  p.seeds = { { 1.5, -2.25, 3.125 }, { 0.1, 0.2, 0.3 } };
  p.fillHoles = false;
  p.closingRadius = 1.25;
  p.minRadius = 0.75;
  p.maxRadius = 3.5;
  p.scales = 6;
  p.alpha = 0.45;
  p.beta = 0.55;
  p.gamma = 7.0;
  p.vesselnessThreshold = 0.0625;
  p.brightVessels = false;
  p.levelSetIterations = 25;
  p.levelSetSigma = 0.8;
  p.levelSetPropagation = -0.3;
  p.levelSetCurvature = 2.5;
  settings.surface.extractor = SurfaceExtractor::Itk;
  settings.surface.smoothing = 0.3;
  settings.surface.targetTriangles = 50000;
  settings.surface.seeds = { { -4.0, 5.0, 6.5 } };
  s.segmentation = settings;

  SessionRibbon ribbon;
  ribbon.ribbon = Ribbon(-3.0, 11.0 / 3.0);
  ribbon.ribbon.extraTurns = -2;
  ribbon.radius = 7.3;
  ribbon.decay.shape = DecayShape::Plateau;
  ribbon.decay.plateau = 0.55;
  ribbon.vesselRadius = 3.3333333333333335;
  s.ribbon = ribbon;
  return s;
}

void ExpectSameEnd(const RibbonEnd& a, const RibbonEnd& b)
{
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_EQ(a.position[i], b.position[i]);
    EXPECT_EQ(a.tangent[i], b.tangent[i]);
    EXPECT_EQ(a.normal[i], b.normal[i]);
  }
}

void ExpectSameRibbon(const RibbonSpec& a, const RibbonSpec& b)
{
  ExpectSameEnd(a.start, b.start);
  ExpectSameEnd(a.end, b.end);
  EXPECT_EQ(a.extraTurns, b.extraTurns);
}

// The message of ReadSessionFile's refusal; empty when it read the file.
std::string ReadError(const std::string& path)
{
  try
  {
    ReadSessionFile(path);
  }
  catch (const SessionFileError& e)
  {
    return e.what();
  }
  return {};
}

// `text` with the first occurrence of `from` replaced by `to` (the test fails when absent).
std::string Replaced(std::string text, const std::string& from, const std::string& to)
{
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos)
  {
    text.replace(at, from.size(), to);
  }
  return text;
}

}

TEST(SessionAutosave, EveryFieldIsReadBackExactly)
{
  TempFolder folder;
  const std::string path = folder.File("autosave.bender-session.json");
  const SessionSnapshot written = FullSnapshot();
  WriteSessionFile(written, path);
  const SessionSnapshot read = ReadSessionFile(path);

  EXPECT_NE(ReadText(path).find("\"version\": 2"), std::string::npos);
  EXPECT_EQ(read.sourcePath, written.sourcePath);
  EXPECT_EQ(read.surfaceName, written.surfaceName);
  EXPECT_EQ(read.frame, written.frame);
  EXPECT_EQ(SerializeWarpPlan(read.plan), SerializeWarpPlan(written.plan));
  ASSERT_EQ(read.plan.warps.size(), 2u);
  EXPECT_EQ(read.plan.warps[0].radius, written.plan.warps[0].radius);
  ExpectSameRibbon(read.plan.warps[0].final, written.plan.warps[0].final);

  ASSERT_TRUE(read.volume.has_value());
  EXPECT_EQ(read.volume->path, written.volume->path);
  EXPECT_EQ(read.volume->name, written.volume->name);
  EXPECT_EQ(read.volume->dicomSeriesUid, written.volume->dicomSeriesUid);
  EXPECT_EQ(read.volume->geometry.size, written.volume->geometry.size);
  EXPECT_EQ(read.volume->geometry.spacing, written.volume->geometry.spacing);
  EXPECT_EQ(read.volume->geometry.origin, written.volume->geometry.origin);
  EXPECT_EQ(read.volume->geometry.direction, written.volume->geometry.direction);
  EXPECT_EQ(read.volume->maskPath, written.volume->maskPath);
  EXPECT_TRUE(SameVolumeGeometry(read.volume->geometry, written.volume->geometry));

  ASSERT_TRUE(read.segmentation.has_value());
  const SegmentationParameters& a = read.segmentation->segmentation;
  const SegmentationParameters& b = written.segmentation->segmentation;
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.lower, b.lower);
  EXPECT_EQ(a.upper, b.upper);
  EXPECT_EQ(a.seeds, b.seeds);
  EXPECT_EQ(a.fillHoles, b.fillHoles);
  EXPECT_EQ(a.closingRadius, b.closingRadius);
  EXPECT_EQ(a.minRadius, b.minRadius);
  EXPECT_EQ(a.maxRadius, b.maxRadius);
  EXPECT_EQ(a.scales, b.scales);
  EXPECT_EQ(a.alpha, b.alpha);
  EXPECT_EQ(a.beta, b.beta);
  EXPECT_EQ(a.gamma, b.gamma);
  EXPECT_EQ(a.vesselnessThreshold, b.vesselnessThreshold);
  EXPECT_EQ(a.brightVessels, b.brightVessels);
  EXPECT_EQ(a.levelSetIterations, b.levelSetIterations);
  EXPECT_EQ(a.levelSetSigma, b.levelSetSigma);
  EXPECT_EQ(a.levelSetPropagation, b.levelSetPropagation);
  EXPECT_EQ(a.levelSetCurvature, b.levelSetCurvature);
  const SurfaceParameters& f = read.segmentation->surface;
  const SurfaceParameters& g = written.segmentation->surface;
  EXPECT_EQ(f.extractor, g.extractor);
  EXPECT_EQ(f.smoothing, g.smoothing);
  EXPECT_EQ(f.targetTriangles, g.targetTriangles);
  EXPECT_EQ(f.seeds, g.seeds);

  ASSERT_TRUE(read.ribbon.has_value());
  ExpectSameRibbon(read.ribbon->ribbon, written.ribbon->ribbon);
  EXPECT_EQ(read.ribbon->radius, written.ribbon->radius);
  EXPECT_EQ(read.ribbon->decay.shape, written.ribbon->decay.shape);
  EXPECT_EQ(read.ribbon->decay.plateau, written.ribbon->decay.plateau);
  EXPECT_EQ(read.ribbon->vesselRadius, written.ribbon->vesselRadius);

  // Written again from what was read: the same file, byte for byte.
  const std::string again = folder.File("again.bender-session.json");
  WriteSessionFile(read, again);
  EXPECT_EQ(ReadText(again), ReadText(path));
}

TEST(SessionAutosave, OptionalPartsStayAbsent)
{
  TempFolder folder;
  const std::string path = folder.File("autosave.bender-session.json");
  SessionSnapshot bare;
  bare.sourcePath = "/data/tube.stl";
  WriteSessionFile(bare, path);
  const std::string text = ReadText(path);
  EXPECT_EQ(text.find("\"volume\""), std::string::npos);
  EXPECT_EQ(text.find("\"segmentation\""), std::string::npos);
  EXPECT_EQ(text.find("\"ribbon\""), std::string::npos);
  const SessionSnapshot read = ReadSessionFile(path);
  EXPECT_EQ(read.sourcePath, bare.sourcePath);
  EXPECT_TRUE(read.surfaceName.empty());
  EXPECT_FALSE(read.volume || read.segmentation || read.ribbon);
}

TEST(SessionAutosave, VersionOneFilesAreStillRead)
{
  // A file as Bender wrote it before the volume, the parameters and the ribbon were kept.
  TempFolder folder;
  const std::string path = folder.File("old.bender-session.json");
  WarpPlan plan = FullSnapshot().plan;
  const std::string text = "{\n  \"format\": \"bender-session\",\n  \"version\": 1,\n"
                           "  \"source\": \"/data/aneurysm.stl\",\n  \"name\": \"aneurysm.stl\",\n"
                           "  \"frame\": \"LPS\",\n  \"plan\": " +
    WarpPlanToJson(plan).dump(2) + "\n}\n";
  WriteText(path, text);
  const SessionSnapshot read = ReadSessionFile(path);
  EXPECT_EQ(read.sourcePath, "/data/aneurysm.stl");
  EXPECT_EQ(read.surfaceName, "aneurysm.stl");
  EXPECT_EQ(SerializeWarpPlan(read.plan), SerializeWarpPlan(plan));
  EXPECT_FALSE(read.volume || read.segmentation || read.ribbon);
}

TEST(SessionAutosave, CorruptFilesAreRefusedNamingTheFileAndTheField)
{
  TempFolder folder;
  const std::string good = folder.File("good.bender-session.json");
  WriteSessionFile(FullSnapshot(), good);
  const std::string text = ReadText(good);
  const std::string bad = folder.File("crashed.bender-session.json");
  const auto refusal = [&](const std::string& content)
  {
    WriteText(bad, content);
    return ReadError(bad);
  };
  const auto expectRefused = [&](const std::string& content, const std::string& field)
  {
    const std::string message = refusal(content);
    EXPECT_EQ(message.rfind("crashed.bender-session.json: ", 0), 0u) << message;
    EXPECT_NE(message.find(field), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };

  EXPECT_EQ(ReadError(good), "");
  // Cut short by a crash mid-write (an atomic write never leaves this, another program may).
  expectRefused(text.substr(0, text.size() / 2), "not valid JSON");
  expectRefused("", "not valid JSON");
  expectRefused("[1, 2]", "format");
  // A format that is not a string (found by fuzz_session: nlohmann's value() threw type_error).
  expectRefused(Replaced(text, "\"format\": \"bender-session\"", "\"format\": 7"), "format");
  expectRefused(Replaced(text, "\"format\": \"bender-session\"", "\"format\": null"), "format");
  expectRefused(Replaced(text, "\"version\": 2", "\"version\": 3"), "version");
  expectRefused(Replaced(text, "\"version\": 2", "\"version\": \"2\""), "version");
  expectRefused(Replaced(text, "\"lower\": 187.25", "\"lower\": \"187.25\""),
    "segmentation.lower: not a finite number");
  expectRefused(Replaced(text, "\"lower\": 187.25", "\"lower\": 3000"), "segmentation");
  expectRefused(
    Replaced(text, "\"method\": \"vesselness\"", "\"method\": \"magic\""), "segmentation.method");
  expectRefused(Replaced(text, "\"smoothing\": 0.3", "\"smoothing\": 4"), "smoothing");
  expectRefused(Replaced(text, "\"fillHoles\": false,", ""), "segmentation.fillHoles: missing");
  expectRefused(Replaced(text, "\"size\": [\n      256", "\"size\": [\n      -256"), "volume.size");
  expectRefused(
    Replaced(text, "\"spacing\": [\n      0.9375", "\"spacing\": [\n      0"), "volume.spacing");
  expectRefused(
    Replaced(text, "\"path\": \"/data/patient 7/dicom\"", "\"path\": 7"), "volume.path");
  expectRefused(Replaced(text, "\"radius\": 7.3", "\"radius\": 0"), "ribbon.radius");
  expectRefused(Replaced(text,
                  "\"decay\": \"plateau\",\n    \"plateau\": 0.55",
                  "\"decay\": \"plateau\",\n    \"plateau\": 2"),
    "ribbon.plateau");
  expectRefused(Replaced(text, "\"extraTurns\": -2", "\"extraTurns\": 0.5"), "ribbon.extraTurns");
  expectRefused(Replaced(text, "\"volume\": {", "\"volume\": 5, \"x\": {"), "volume");
  // The plan's own rules (ReadWarpPlan's).
  expectRefused(Replaced(text, "\"radius\": 7.5", "\"radius\": -7.5"), "plan");
  // A missing file.
  const std::string missing = ReadError(folder.File("none.bender-session.json"));
  EXPECT_NE(missing.find("none.bender-session.json"), std::string::npos) << missing;
}

TEST(SessionAutosave, ASnapshotThatCannotBeWrittenLeavesThePreviousFile)
{
  TempFolder folder;
  const std::string path = folder.File("autosave.bender-session.json");
  WriteSessionFile(FullSnapshot(), path);
  const std::string before = ReadText(path);
  SessionSnapshot broken = FullSnapshot();
  broken.segmentation->segmentation.lower = std::numeric_limits<double>::quiet_NaN();
  try
  {
    WriteSessionFile(broken, path);
    FAIL() << "a NaN parameter was written";
  }
  catch (const SessionFileError& e)
  {
    EXPECT_NE(std::string(e.what()).find("autosave.bender-session.json: segmentation.lower"),
      std::string::npos)
      << e.what();
  }
  EXPECT_EQ(ReadText(path), before);
  // Only the session file in the folder: no temporary left behind.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(folder.path),
              std::filesystem::directory_iterator()),
    1);
}

TEST(SessionAutosave, VolumeIdentity)
{
  ImageGeometry a;
  a.size = { 64, 64, 40 };
  a.spacing = { 0.5, 0.5, 1.2 };
  a.origin = { -16.0, -16.0, 10.0 };
  ImageGeometry b = a;
  EXPECT_TRUE(SameVolumeGeometry(a, b));
  b.origin[2] += 1e-9; // written and read back with rounding: the same volume
  EXPECT_TRUE(SameVolumeGeometry(a, b));
  b = a;
  b.size[2] = 41;
  EXPECT_FALSE(SameVolumeGeometry(a, b));
  b = a;
  b.spacing[0] = 0.6;
  EXPECT_FALSE(SameVolumeGeometry(a, b));
  b = a;
  b.origin[1] = -15.0;
  EXPECT_FALSE(SameVolumeGeometry(a, b));
  b = a;
  b.direction = { 0, 1, 0, 1, 0, 0, 0, 0, 1 };
  EXPECT_FALSE(SameVolumeGeometry(a, b));
  EXPECT_EQ(DescribeVolumeGeometry(a), "64x64x40 voxels of 0.5x0.5x1.2 mm at (-16, -16, 10)");
}

namespace
{
std::shared_ptr<const Volume> SmallVolume(std::size_t n, float offset)
{
  auto volume = std::make_shared<Volume>();
  volume->geometry.size = { n, n + 1, n + 2 };
  volume->geometry.spacing = { 0.5, 0.75, 1.25 };
  volume->voxels.resize(volume->geometry.VoxelCount());
  for (std::size_t i = 0; i < volume->voxels.size(); ++i)
  {
    volume->voxels[i] = offset + static_cast<float>(i % 97);
  }
  return volume;
}
} // namespace

// The window's copy of the demo volume beside the autosave (issue: it was written on the GUI
// thread, inside the autosave): written on a thread of its own, referenced only once complete.
// The write is held at a gate the test opens, so what the caller sees during the write is
// checked without any timing.
TEST(AutosaveCopies, WrittenOffTheCallersThreadAndReferencedOnlyWhenComplete)
{
  TempFolder folder;
  const std::string path = SessionVolumeCopyPath((folder.path / "autosave.json").string());
  const std::shared_ptr<const Volume> a = SmallVolume(6, 0.0f);
  const std::shared_ptr<const Volume> b = SmallVolume(9, 1000.0f);

  std::atomic<int> finished{ 0 };
  std::atomic<int> writes{ 0 };
  std::promise<void> gate;
  std::shared_future<void> opened = gate.get_future().share();
  std::thread::id writer;
  AutosaveCopies copies([&]() { ++finished; });
  const auto gatedWrite = [&](const std::shared_ptr<const Volume>& volume)
  {
    return [&, volume](const std::string& to)
    {
      ++writes;
      writer = std::this_thread::get_id();
      // Bounded, so that a regression (the write on the caller's thread) fails instead of
      // hanging: the caller's thread id is then checked below.
      opened.wait_for(std::chrono::seconds(30));
      WriteVolume(*volume, to);
    };
  };

  std::string problem;
  EXPECT_EQ(copies.CopyOf(a, path, gatedWrite(a), problem), ""); // started, not complete
  EXPECT_TRUE(problem.empty());
  // The caller is back while the write waits at the gate: nothing references the copy yet,
  // and asking again (the next autosave) or for another volume starts no second write.
  EXPECT_TRUE(copies.IsWriting());
  EXPECT_EQ(copies.CopyOf(a, path, gatedWrite(a), problem), "");
  EXPECT_EQ(copies.CopyOf(b, path, gatedWrite(b), problem), "");
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_EQ(finished.load(), 0);
  gate.set_value();
  copies.Wait();
  EXPECT_NE(writer, std::this_thread::get_id());
  EXPECT_EQ(writes.load(), 1);
  EXPECT_EQ(finished.load(), 1);
  EXPECT_FALSE(copies.IsWriting());

  // Complete: referenced, and the file is the volume, voxel for voxel.
  EXPECT_EQ(copies.CopyOf(a, path, gatedWrite(a), problem), path);
  EXPECT_EQ(ReadVolume(path).voxels, a->voxels);
  // No staging file left beside it.
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder.path))
  {
    (void)entry;
    ++files;
  }
  EXPECT_EQ(files, 1);

  // Another volume replaces it: from the moment its write starts the old one is no longer
  // referenced (the file will hold the new one), and the new one only once written.
  EXPECT_EQ(copies.CopyOf(b, path, gatedWrite(b), problem), "");
  EXPECT_EQ(copies.CopyOf(a, path, gatedWrite(a), problem), "");
  copies.Wait();
  EXPECT_EQ(finished.load(), 2);
  EXPECT_EQ(copies.CopyOf(b, path, gatedWrite(b), problem), path);
  EXPECT_EQ(ReadVolume(path).voxels, b->voxels);
}

TEST(AutosaveCopies, AFailedWriteIsSaidOnceAndNotRetriedForTheSameObject)
{
  TempFolder folder;
  const std::string path = (folder.path / "missing-folder" / "copy.nrrd").string();
  const std::shared_ptr<const Volume> a = SmallVolume(4, 0.0f);
  std::atomic<int> finished{ 0 };
  std::atomic<int> writes{ 0 };
  AutosaveCopies copies([&]() { ++finished; });
  const auto write = [&](const std::string& to)
  {
    ++writes;
    WriteVolume(*a, to);
  };
  std::string problem;
  EXPECT_EQ(copies.CopyOf(a, path, write, problem), "");
  copies.Wait();
  EXPECT_EQ(finished.load(), 1); // the owner autosaves again, and hears of the problem
  EXPECT_EQ(copies.CopyOf(a, path, write, problem), "");
  EXPECT_NE(problem.find("missing-folder"), std::string::npos) << problem;
  EXPECT_EQ(copies.CopyOf(a, path, write, problem), "");
  EXPECT_TRUE(problem.empty()) << problem;
  copies.Wait();
  EXPECT_EQ(writes.load(), 1);
  EXPECT_FALSE(std::filesystem::exists(path));
}
