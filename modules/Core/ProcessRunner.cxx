#include "ProcessRunner.h"

#include "BenderErrors.h"

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <sstream>

#include <csignal>
#include <fcntl.h>
#include <poll.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

namespace bender
{

namespace
{

using Clock = std::chrono::steady_clock;

// The argument vector for exec, made before fork (the child must not allocate).
struct ExecArguments
{
  std::string program;
  std::vector<std::string> args;
  std::vector<char*> pointers;

  explicit ExecArguments(const std::vector<std::string>& argv)
  {
    if (argv.empty() || argv[0].empty())
    {
      throw EnvironmentError("no program to run");
    }
    this->program = FindExecutable(argv[0]);
    if (this->program.empty())
    {
      throw EnvironmentError(argv[0] + ": cannot be started: not found on PATH");
    }
    this->args = argv;
    for (std::string& a : this->args)
    {
      this->pointers.push_back(a.data());
    }
    this->pointers.push_back(nullptr);
  }
};

// In the child: stdin from /dev/null, stdout and stderr to `output` (-1: unchanged), then
// exec. A failure before exec is reported as its errno through `report` (close-on-exec).
[[noreturn]] void ExecChild(const ExecArguments& exec,
  const std::string& folder,
  int output,
  int report,
  bool ownGroup)
{
  if (ownGroup)
  {
    ::setpgid(0, 0);
  }
  const int devNull = ::open("/dev/null", O_RDONLY);
  if (devNull >= 0)
  {
    ::dup2(devNull, STDIN_FILENO);
  }
  if (output >= 0)
  {
    ::dup2(output, STDOUT_FILENO);
    ::dup2(output, STDERR_FILENO);
  }
  if (folder.empty() || ::chdir(folder.c_str()) == 0)
  {
    ::execv(exec.program.c_str(), exec.pointers.data());
  }
  const int error = errno;
  [[maybe_unused]] const ssize_t written = ::write(report, &error, sizeof(error));
  ::_exit(127);
}

// Forks and execs; returns the child's id once exec succeeded. Closes `childOutput` in the
// parent. Throws EnvironmentError naming the program when it could not be started.
pid_t Spawn(const ExecArguments& exec,
  const std::string& folder,
  int childOutput,
  bool ownGroup,
  const std::string& name)
{
  int report[2];
  if (::pipe2(report, O_CLOEXEC) != 0)
  {
    throw EnvironmentError(name + ": cannot be started: " + std::strerror(errno));
  }
  // One fork at a time in the process: libraries' fork handlers are not safe against a fork
  // on another thread (ITK 5.2's thread pool joins its threads before a fork and starts new
  // ones after it; two flow cases started at once deadlocked in it). The parent holds the lock
  // until fork returns; the child execs.
  static std::mutex forking;
  pid_t pid = -1;
  int forkError = 0;
  {
    const std::lock_guard<std::mutex> lock(forking);
    pid = ::fork();
    forkError = errno;
  }
  if (pid < 0)
  {
    ::close(report[0]);
    ::close(report[1]);
    throw EnvironmentError(name + ": cannot be started: " + std::strerror(forkError));
  }
  if (pid == 0)
  {
    ::close(report[0]);
    ExecChild(exec, folder, childOutput, report[1], ownGroup);
  }
  ::close(report[1]);
  if (childOutput >= 0)
  {
    ::close(childOutput);
  }
  int error = 0;
  ssize_t n;
  while ((n = ::read(report[0], &error, sizeof(error))) < 0 && errno == EINTR)
  {
  }
  ::close(report[0]);
  if (n == static_cast<ssize_t>(sizeof(error)))
  {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR)
    {
    }
    throw EnvironmentError(name + ": cannot be started" +
      (folder.empty() ? std::string() : " in " + folder) + ": " + std::strerror(error));
  }
  return pid;
}

// Ends `pid` (its group when it has its own): SIGTERM first, SIGKILL after the grace period.
void Signal(pid_t pid, bool ownGroup, int signal)
{
  ::kill(ownGroup ? -pid : pid, signal);
}

} // namespace

std::string FindExecutable(const std::string& name)
{
  if (name.empty())
  {
    return {};
  }
  if (name.find('/') != std::string::npos)
  {
    return ::access(name.c_str(), X_OK) == 0 ? name : std::string();
  }
  const char* path = std::getenv("PATH");
  std::istringstream folders(path ? path : "/usr/bin:/bin");
  std::string folder;
  while (std::getline(folders, folder, ':'))
  {
    const std::string candidate = (folder.empty() ? std::string(".") : folder) + "/" + name;
    if (::access(candidate.c_str(), X_OK) == 0)
    {
      return candidate;
    }
  }
  return {};
}

ProcessResult RunProcess(const ProcessOptions& options)
{
  const ExecArguments exec(options.argv);
  const std::string& name = options.argv[0];
  std::ofstream log;
  if (!options.logPath.empty())
  {
    log.open(options.logPath, options.appendLog ? std::ios::app : std::ios::trunc);
    if (!log)
    {
      throw EnvironmentError(options.logPath + ": cannot be written (" + name + "'s log)");
    }
  }
  int output[2];
  if (::pipe2(output, O_CLOEXEC) != 0)
  {
    throw EnvironmentError(name + ": cannot be started: " + std::strerror(errno));
  }
  // dup2 in the child clears close-on-exec on stdout and stderr: only the pipe's copies close.
  const bool stoppable = options.timeoutSeconds > 0.0 || options.cancel;
  pid_t pid;
  try
  {
    pid = Spawn(exec, options.workingDirectory, output[1], stoppable, name);
  }
  catch (...)
  {
    ::close(output[0]);
    throw;
  }

  ProcessResult result;
  const Clock::time_point start = Clock::now();
  Clock::time_point termSent{};
  bool stopping = false, killed = false;
  std::string pending;
  char buffer[4096];
  for (;;)
  {
    if (stoppable && !stopping)
    {
      const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
      result.timedOut = options.timeoutSeconds > 0.0 && elapsed >= options.timeoutSeconds;
      result.cancelled = !result.timedOut && options.cancel && options.cancel->load();
      if (result.timedOut || result.cancelled)
      {
        Signal(pid, stoppable, SIGTERM);
        stopping = true;
        termSent = Clock::now();
      }
    }
    if (stopping && !killed && Clock::now() - termSent > std::chrono::seconds(2))
    {
      Signal(pid, stoppable, SIGKILL);
      killed = true;
    }
    pollfd ready{ output[0], POLLIN, 0 };
    const int polled = ::poll(&ready, 1, stoppable ? 100 : -1);
    if (polled < 0 && errno != EINTR)
    {
      break;
    }
    if (polled <= 0)
    {
      continue;
    }
    const ssize_t n = ::read(output[0], buffer, sizeof(buffer));
    if (n < 0 && errno == EINTR)
    {
      continue;
    }
    if (n <= 0)
    {
      break;
    }
    if (log.is_open())
    {
      log.write(buffer, n);
    }
    pending.append(buffer, static_cast<std::size_t>(n));
    std::size_t eol;
    while ((eol = pending.find('\n')) != std::string::npos)
    {
      const std::string line = pending.substr(0, eol);
      pending.erase(0, eol + 1);
      if (!line.empty())
      {
        result.lastLine = line;
      }
      if (options.onLine)
      {
        options.onLine(line);
      }
    }
  }
  ::close(output[0]);
  if (log.is_open())
  {
    log.close();
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR)
  {
  }
  if (WIFEXITED(status))
  {
    result.exitCode = WEXITSTATUS(status);
  }
  else if (WIFSIGNALED(status))
  {
    result.signal = WTERMSIG(status);
  }
  return result;
}

BackgroundProcess::~BackgroundProcess()
{
  this->Stop();
}

void BackgroundProcess::Start(const std::vector<std::string>& argv)
{
  if (this->Running())
  {
    throw InputError((argv.empty() ? std::string("a program") : argv[0]) +
      ": cannot be started: one is already running");
  }
  const ExecArguments exec(argv);
  this->Pid = Spawn(exec, std::string(), -1, false, argv[0]);
}

bool BackgroundProcess::Running()
{
  if (this->Pid <= 0)
  {
    return false;
  }
  int status = 0;
  if (::waitpid(static_cast<pid_t>(this->Pid), &status, WNOHANG) == this->Pid)
  {
    this->Pid = -1;
    return false;
  }
  return true;
}

void BackgroundProcess::Stop()
{
  if (this->Pid <= 0)
  {
    return;
  }
  const pid_t pid = static_cast<pid_t>(this->Pid);
  this->Pid = -1;
  ::kill(pid, SIGTERM);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR)
  {
  }
}

} // namespace bender
