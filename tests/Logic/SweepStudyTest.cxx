// A sweep folder read back for the window (SweepStudy.h) and the window's local sweep refusing
// what it cannot run, without OpenFOAM.

#include "SweepStudy.h"

#include "BenderErrors.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

using namespace bender;
namespace fs = std::filesystem;

namespace
{
/// A fresh empty folder under the system temporary folder, removed at the end.
class Folder
{
public:
  explicit Folder(const std::string& name)
    : Path(fs::temp_directory_path() / (name + "-" + std::to_string(std::random_device{}())))
  {
    fs::remove_all(this->Path);
    fs::create_directories(this->Path);
  }
  ~Folder() { fs::remove_all(this->Path); }
  fs::path Path;
};

void Write(const fs::path& path, const std::string& text)
{
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

/// sweep.json of a fraction sweep c00 (0), c01 (0.5), c02 (1) with hashes h0, h1, h2.
std::string SweepJson()
{
  nlohmann::json j;
  j["format"] = "bender-sweep";
  j["version"] = 1;
  j["parameter"] = "fraction";
  j["candidates"] = nlohmann::json::array();
  const double values[3] = { 0.0, 0.5, 1.0 };
  for (int i = 0; i < 3; ++i)
  {
    j["candidates"].push_back({ { "id", "c0" + std::to_string(i) },
      { "value", values[i] },
      { "plan", "bend.json" },
      { "hash", "h" + std::to_string(i) } });
  }
  return j.dump(2);
}

SweepRow Row(const std::string& id, double value, const std::string& hash)
{
  SweepRow row;
  row.id = id;
  row.parameter = "fraction";
  row.value = value;
  row.planName = "bend.json";
  row.original = value == 0.0;
  row.hash = hash;
  row.state = "solved";
  row.pressureDrop = 12.5;
  row.outlets.push_back({ "outlet", 100.0, 12.5, 600.0 });
  row.meshCells = 4200;
  row.iterations = 80;
  return row;
}
} // namespace

TEST(SweepStudy, AFolderWithoutASweepIsRefusedNamingIt)
{
  Folder folder("bender_sweep_study_empty");
  try
  {
    ReadSweepFolder(folder.Path.string());
    FAIL() << "no error";
  }
  catch (const InputError& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find(folder.Path.string()), std::string::npos) << what;
    EXPECT_NE(what.find("not a sweep folder"), std::string::npos) << what;
  }
  Write(folder.Path / "sweep.json", "{ not json");
  try
  {
    ReadSweepFolder(folder.Path.string());
    FAIL() << "no error";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("sweep.json"), std::string::npos) << e.what();
  }
}

TEST(SweepStudy, TheRowsAreAsTheCandidatesLeftThem)
{
  Folder folder("bender_sweep_study_rows");
  Write(folder.Path / "sweep.json", SweepJson());
  const SweepRow solved = Row("c00", 0.0, "h0");
  Write(folder.Path / "c00" / "state.json", SweepRowToJson(solved));
  // c01's state is of other inputs; c02 has none.
  Write(folder.Path / "c01" / "state.json", SweepRowToJson(Row("c01", 0.5, "another")));
  const SweepFolder sweep = ReadSweepFolder(folder.Path.string());
  EXPECT_EQ(sweep.parameter, "fraction");
  ASSERT_EQ(sweep.rows.size(), 3u);
  // The state.json written for the same inputs, as written.
  EXPECT_EQ(SweepRowToJson(sweep.rows[0]), SweepRowToJson(solved));
  EXPECT_EQ(sweep.rows[1].state, "missing");
  EXPECT_NE(sweep.rows[1].reason.find("other inputs"), std::string::npos);
  EXPECT_EQ(sweep.rows[1].hash, "h1");
  EXPECT_EQ(sweep.rows[2].state, "missing");
  EXPECT_EQ(sweep.rows[2].value, 1.0);
  const SweepRow* original = SweepOriginalRow(sweep.rows);
  ASSERT_NE(original, nullptr);
  EXPECT_EQ(original->id, "c00");
  EXPECT_EQ(
    fs::path(SweepCaseFolder(sweep, *original)), fs::absolute(folder.Path / "c00" / "case"));
}

TEST(SweepStudy, TheSessionsSweepRefusesWhatItCannotRun)
{
  Folder folder("bender_sweep_study_refused");
  SessionSweepInput input;
  input.first = vtkSmartPointer<vtkPolyData>::New();
  input.name = "tube";
  SessionSweepOptions options;
  options.folder = (folder.Path / "sweep").string();
  // No bend: nothing to vary.
  EXPECT_THROW(RunSessionSweep(input, options), InputError);
  try
  {
    RunSessionSweep(input, options);
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("tube: no bend"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(options.folder));
  // A folder that holds something else than a sweep is left alone.
  input.plan.warps.emplace_back();
  Write(folder.Path / "other" / "notes.txt", "mine");
  options.folder = (folder.Path / "other").string();
  try
  {
    RunSessionSweep(input, options);
    FAIL() << "no error";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("holds other files"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(folder.Path / "other" / "input"));
}
