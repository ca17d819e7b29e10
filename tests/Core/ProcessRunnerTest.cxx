// The one process runner: output lines and log, working folder, exit status, timeout and
// cancellation (the program and what it started are stopped), programs that cannot start, and
// a program left running in the background.

#include "ProcessRunner.h"
#include "BenderErrors.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <csignal>
#include <unistd.h>

namespace fs = std::filesystem;

namespace
{

class ProcessRunnerTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    this->Dir = fs::temp_directory_path() /
      ("bender-process-" + std::to_string(::getpid()) + "-" +
        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(this->Dir);
    fs::create_directories(this->Dir);
  }
  void TearDown() override { fs::remove_all(this->Dir); }
  static std::string Read(const fs::path& path)
  {
    std::ifstream in(path);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  fs::path Dir;
};

double Seconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

TEST_F(ProcessRunnerTest, LinesLogFolderAndExitStatus)
{
  bender::ProcessOptions options;
  options.argv = { "sh", "-c", "pwd; echo out; echo err >&2; printf tail; exit 3" };
  options.workingDirectory = this->Dir.string();
  options.logPath = (this->Dir / "run.log").string();
  std::vector<std::string> lines;
  options.onLine = [&lines](const std::string& line) { lines.push_back(line); };
  const bender::ProcessResult result = bender::RunProcess(options);
  EXPECT_EQ(result.exitCode, 3);
  EXPECT_EQ(result.signal, 0);
  EXPECT_FALSE(result.Succeeded());
  ASSERT_EQ(lines.size(), 3u) << "an unterminated last line is in the log, not a line";
  EXPECT_TRUE(fs::equivalent(lines[0], this->Dir)) << lines[0];
  EXPECT_EQ(lines[1], "out");
  EXPECT_EQ(lines[2], "err");
  EXPECT_EQ(result.lastLine, "err");
  const std::string log = Read(this->Dir / "run.log");
  EXPECT_EQ(log, lines[0] + "\nout\nerr\ntail");

  // Appending keeps the first run's log; a clean exit succeeds.
  options.argv = { "sh", "-c", "echo again" };
  options.appendLog = true;
  options.onLine = nullptr;
  EXPECT_TRUE(bender::RunProcess(options).Succeeded());
  EXPECT_EQ(Read(this->Dir / "run.log"), log + "again\n");
  options.appendLog = false;
  EXPECT_TRUE(bender::RunProcess(options).Succeeded());
  EXPECT_EQ(Read(this->Dir / "run.log"), "again\n");
}

TEST_F(ProcessRunnerTest, TimeoutStopsTheProgramAndWhatItStarted)
{
  const fs::path marker = this->Dir / "child-survived";
  bender::ProcessOptions options;
  // The shell starts a child that would write the marker after 1.5 s.
  options.argv = { "sh", "-c", "(sleep 1.5; touch '" + marker.string() + "') & wait" };
  options.timeoutSeconds = 0.3;
  const auto start = std::chrono::steady_clock::now();
  const bender::ProcessResult result = bender::RunProcess(options);
  EXPECT_LT(Seconds(start), 1.2);
  EXPECT_TRUE(result.timedOut);
  EXPECT_FALSE(result.cancelled);
  EXPECT_FALSE(result.Succeeded());
  EXPECT_EQ(result.signal, SIGTERM);
  std::this_thread::sleep_for(std::chrono::milliseconds(1600));
  EXPECT_FALSE(fs::exists(marker)) << "the program's own child was left running";
}

TEST_F(ProcessRunnerTest, CancelFlagStopsIt)
{
  std::atomic<bool> cancel{ false };
  bender::ProcessOptions options;
  options.argv = { "sleep", "30" };
  options.cancel = &cancel;
  std::thread canceller(
    [&cancel]
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      cancel = true;
    });
  const auto start = std::chrono::steady_clock::now();
  const bender::ProcessResult result = bender::RunProcess(options);
  canceller.join();
  EXPECT_LT(Seconds(start), 5.0);
  EXPECT_TRUE(result.cancelled);
  EXPECT_FALSE(result.timedOut);
  EXPECT_FALSE(result.Succeeded());
}

TEST_F(ProcessRunnerTest, ProgramsThatCannotStartAreEnvironmentErrors)
{
  bender::ProcessOptions options;
  options.argv = { "bender-no-such-program-here" };
  try
  {
    bender::RunProcess(options);
    FAIL() << "a missing program was run";
  }
  catch (const bender::EnvironmentError& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("bender-no-such-program-here"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  options.argv = { "sh", "-c", "true" };
  options.workingDirectory = (this->Dir / "missing").string();
  try
  {
    bender::RunProcess(options);
    FAIL() << "ran in a missing folder";
  }
  catch (const bender::EnvironmentError& e)
  {
    EXPECT_NE(std::string(e.what()).find("missing"), std::string::npos) << e.what();
  }
  options.workingDirectory.clear();
  options.logPath = (this->Dir / "missing" / "log").string();
  EXPECT_THROW(bender::RunProcess(options), bender::EnvironmentError);
  options.argv.clear();
  EXPECT_THROW(bender::RunProcess(options), bender::EnvironmentError);
}

TEST_F(ProcessRunnerTest, FindExecutableSearchesPath)
{
  const std::string sh = bender::FindExecutable("sh");
  ASSERT_FALSE(sh.empty());
  EXPECT_TRUE(fs::exists(sh));
  EXPECT_EQ(bender::FindExecutable(sh), sh);
  EXPECT_EQ(bender::FindExecutable("bender-no-such-program-here"), "");
  EXPECT_EQ(bender::FindExecutable((this->Dir / "nothing").string()), "");
}

TEST_F(ProcessRunnerTest, BackgroundProcessRunsUntilStopped)
{
  bender::BackgroundProcess process;
  EXPECT_FALSE(process.Running());
  process.Start({ "sleep", "30" });
  EXPECT_TRUE(process.Running());
  EXPECT_THROW(process.Start({ "sleep", "30" }), bender::InputError);
  const auto start = std::chrono::steady_clock::now();
  process.Stop();
  EXPECT_LT(Seconds(start), 5.0);
  EXPECT_FALSE(process.Running());
  // One that exits by itself is seen as ended.
  process.Start({ "sh", "-c", "exit 0" });
  for (int i = 0; i < 100 && process.Running(); ++i)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_FALSE(process.Running());
  EXPECT_THROW(process.Start({ "bender-no-such-program-here" }), bender::EnvironmentError);
}

} // namespace
