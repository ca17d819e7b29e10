// The private Xvfb of the headless commands (app/cli/HeadlessDisplay): one line when it
// cannot start one, DISPLAY pointed at a running server when it can. Each test runs in its own
// process (ctest runs the discovered tests separately): the display is decided once a process.

#include "HeadlessDisplay.h"
#include "ProcessRunner.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include <unistd.h>

namespace fs = std::filesystem;

namespace
{

TEST(HeadlessDisplay, AnExistingDisplayIsKept)
{
  ::setenv("DISPLAY", ":bender-test", 1);
  EXPECT_EQ(bender::EnsureHeadlessDisplay(), "");
  EXPECT_STREQ(std::getenv("DISPLAY"), ":bender-test");
}

TEST(HeadlessDisplay, WithoutXvfbTheReasonIsOneLine)
{
  ::unsetenv("DISPLAY");
  const fs::path empty =
    fs::temp_directory_path() / ("bender-no-xvfb-" + std::to_string(::getpid()));
  fs::create_directories(empty);
  ::setenv("PATH", empty.c_str(), 1);
  const std::string problem = bender::EnsureHeadlessDisplay();
  fs::remove_all(empty);
  EXPECT_NE(problem.find("Xvfb"), std::string::npos) << problem;
  EXPECT_EQ(problem.find('\n'), std::string::npos) << problem;
  EXPECT_EQ(std::getenv("DISPLAY"), nullptr);
  EXPECT_EQ(bender::EnsureHeadlessDisplay(), problem) << "decided once";
}

TEST(HeadlessDisplay, StartsAPrivateXvfb)
{
  if (bender::FindExecutable("Xvfb").empty())
  {
    GTEST_SKIP() << "Xvfb is not installed";
  }
  ::unsetenv("DISPLAY");
  ASSERT_EQ(bender::EnsureHeadlessDisplay(), "");
  const char* display = std::getenv("DISPLAY");
  ASSERT_NE(display, nullptr);
  ASSERT_EQ(display[0], ':');
  EXPECT_TRUE(fs::exists(std::string("/tmp/.X11-unix/X") + (display + 1))) << display;
  EXPECT_EQ(bender::EnsureHeadlessDisplay(), "");
}

} // namespace
