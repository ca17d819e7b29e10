// Shared helpers of the bender-cli end-to-end tests: run the real executable, scratch folders.
#ifndef bender_CliPostTestUtilities_h
#define bender_CliPostTestUtilities_h

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace clitest
{
namespace fs = std::filesystem;

inline const std::string Cli = BENDER_CLI_PATH;
inline const std::string Data = BENDER_TEST_DATA_DIR;
inline const std::string External = BENDER_EXTERNAL_DATA_DIR;
inline const std::string Examples = std::string(BENDER_SOURCE_DIR) + "/examples/";

struct Result
{
  int status = -1;    ///< exit status; -1 when the process did not exit normally
  std::string output; ///< stdout
  std::string errors; ///< stderr
};

inline std::string ReadText(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return { std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
}

/// Runs bender-cli with args (already quoted as needed); stderr goes to a scratch file.
inline Result RunCli(const std::string& args, const fs::path& scratch)
{
  Result r;
  const std::string errFile = (scratch / ".stderr").string();
  const std::string cmd = Cli + " " + args + " 2>'" + errFile + "'";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p)
  {
    return r;
  }
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), static_cast<int>(buf.size()), p))
  {
    r.output += buf.data();
  }
  const int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.errors = ReadText(errFile);
  fs::remove(errFile);
  return r;
}

inline std::string Q(const std::string& path)
{
  return "'" + path + "'";
}

/// A fresh scratch folder per test, removed afterwards.
class ScratchTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Dir = fs::temp_directory_path() /
      ("bender-cli-post-" + std::to_string(::getpid()) + "-" +
        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(this->Dir);
    fs::create_directories(this->Dir);
  }
  void TearDown() override { fs::remove_all(this->Dir); }
  std::string Tmp(const std::string& name) const { return (this->Dir / name).string(); }
  Result Run(const std::string& args) const { return RunCli(args, this->Dir); }
  /// Names of the files in the scratch folder.
  std::vector<std::string> Files() const
  {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(this->Dir))
    {
      names.push_back(e.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }
  fs::path Dir;
};

} // namespace clitest

#define REQUIRE_FILE(path)                                                                         \
  if (!std::filesystem::exists(path))                                                              \
  {                                                                                                \
    GTEST_FAIL() << (path) << " is missing: run scripts/fetch-data";                               \
  }

#endif
