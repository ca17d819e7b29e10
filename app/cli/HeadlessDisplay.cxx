#include "HeadlessDisplay.h"

#include "BenderErrors.h"
#include "ProcessRunner.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <thread>

namespace bender
{

namespace
{

// Starts Xvfb on the first free display number and points DISPLAY at it; "" when it runs.
std::string StartXvfb(BackgroundProcess& server)
{
  const std::string xvfb = FindExecutable("Xvfb");
  if (xvfb.empty())
  {
    return "no display: DISPLAY is not set and Xvfb is not installed (install xvfb, or run "
           "under xvfb-run -a)";
  }
  namespace fs = std::filesystem;
  for (int number = 91; number < 140; ++number)
  {
    const std::string socket = "/tmp/.X11-unix/X" + std::to_string(number);
    const std::string lock = "/tmp/.X" + std::to_string(number) + "-lock";
    std::error_code error;
    if (fs::exists(socket, error) || fs::exists(lock, error))
    {
      continue;
    }
    const std::string display = ":" + std::to_string(number);
    try
    {
      server.Start({ xvfb, display, "-screen", "0", "1280x1024x24", "-nolisten", "tcp" });
    }
    catch (const EnvironmentError&)
    {
      break;
    }
    for (int wait = 0; wait < 100; ++wait)
    {
      if (fs::exists(socket, error))
      {
        ::setenv("DISPLAY", display.c_str(), 1);
        return {};
      }
      if (!server.Running())
      {
        break; // this display number was taken meanwhile: try the next
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    server.Stop();
  }
  return "no display: DISPLAY is not set and a private Xvfb could not be started";
}

} // namespace

std::string EnsureHeadlessDisplay()
{
  static std::mutex mutex;
  static BackgroundProcess server;
  static std::string problem;
  static bool tried = false;
  std::lock_guard<std::mutex> lock(mutex);
  const char* display = std::getenv("DISPLAY");
  if (display && *display)
  {
    return {};
  }
  if (!tried)
  {
    tried = true;
    problem = StartXvfb(server);
  }
  return problem;
}

} // namespace bender
