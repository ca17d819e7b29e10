#include "CfdResidualMonitor.h"

#include "CfdCaseFile.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace fs = std::filesystem;

namespace bender
{

namespace
{
constexpr const char* InitialSuffix = "_initial";

std::vector<std::string> Words(const std::string& line)
{
  std::istringstream in(line);
  std::vector<std::string> words;
  std::string w;
  while (in >> w)
  {
    words.push_back(w);
  }
  return words;
}

/// The solverInfo.dat of the latest start time; empty when there is none yet.
std::string LatestSolverInfo(const std::string& caseDirectory)
{
  const fs::path folder = fs::path(caseDirectory) / "postProcessing" / "solverInfo";
  std::error_code ec;
  std::string latest;
  double latestTime = -1.0;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
  {
    const std::string name = it->path().filename().string();
    char* stop = nullptr;
    const double time = std::strtod(name.c_str(), &stop);
    const fs::path file = it->path() / "solverInfo.dat";
    if (stop && *stop == '\0' && time > latestTime && fs::exists(file, ec))
    {
      latestTime = time;
      latest = file.string();
    }
  }
  return latest;
}
} // namespace

std::vector<CfdIteration> ParseSolverInfo(const std::string& text)
{
  std::vector<CfdIteration> iterations;
  std::vector<std::pair<std::size_t, std::string>> columns; // data column -> field
  std::size_t start = 0;
  // Only whole lines: the writer may be in the middle of the last one.
  for (std::size_t end = text.find('\n'); end != std::string::npos;
       start = end + 1, end = text.find('\n', start))
  {
    const std::vector<std::string> words = Words(text.substr(start, end - start));
    if (words.empty())
    {
      continue;
    }
    if (words[0] == "#")
    {
      if (words.size() > 1 && words[1] == "Time")
      {
        columns.clear();
        const std::string suffix = InitialSuffix;
        for (std::size_t c = 1; c < words.size(); ++c)
        {
          const std::string& h = words[c];
          if (h.size() > suffix.size() &&
            h.compare(h.size() - suffix.size(), suffix.size(), suffix) == 0)
          {
            columns.emplace_back(c - 1, h.substr(0, h.size() - suffix.size()));
          }
        }
      }
      continue;
    }
    CfdIteration row;
    char* stop = nullptr;
    const double time = std::strtod(words[0].c_str(), &stop);
    if (!stop || *stop != '\0' || !std::isfinite(time))
    {
      continue;
    }
    row.iteration = static_cast<int>(std::lround(time));
    bool complete = true;
    for (const auto& [column, field] : columns)
    {
      const double value =
        column < words.size() ? std::strtod(words[column].c_str(), &stop) : std::nan("");
      complete = complete && column < words.size() && stop && *stop == '\0';
      row.residuals.emplace_back(field, value);
    }
    if (complete)
    {
      iterations.push_back(std::move(row));
    }
  }
  return iterations;
}

CfdResidualMonitor::CfdResidualMonitor(std::string caseDirectory,
  std::function<void(const CfdIteration&)> onIteration,
  int intervalMs)
  : CaseDirectory(std::move(caseDirectory))
  , OnIteration(std::move(onIteration))
  , IntervalMs(intervalMs)
{
  this->Thread = std::thread([this]() { this->Loop(); });
}

CfdResidualMonitor::~CfdResidualMonitor()
{
  this->Stop();
}

void CfdResidualMonitor::Stop()
{
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    if (this->Stopping && !this->Thread.joinable())
    {
      return;
    }
    this->Stopping = true;
  }
  this->Wake.notify_all();
  if (this->Thread.joinable())
  {
    this->Thread.join();
  }
}

void CfdResidualMonitor::Loop()
{
  std::unique_lock<std::mutex> lock(this->Mutex);
  for (;;)
  {
    this->Wake.wait_for(
      lock, std::chrono::milliseconds(this->IntervalMs), [this]() { return this->Stopping; });
    const bool last = this->Stopping; // Stop(): one last read
    lock.unlock();
    this->Poll();
    lock.lock();
    if (last)
    {
      return;
    }
  }
}

void CfdResidualMonitor::Poll()
{
  const std::string file = LatestSolverInfo(this->CaseDirectory);
  if (file.empty())
  {
    return;
  }
  if (file != this->File)
  {
    this->File = file;
    this->LastIteration = -1;
  }
  for (const CfdIteration& row : ParseSolverInfo(ReadTextFile(file)))
  {
    if (row.iteration <= this->LastIteration)
    {
      continue;
    }
    this->LastIteration = row.iteration;
    ++this->Reported;
    if (this->OnIteration)
    {
      this->OnIteration(row);
    }
  }
}

} // namespace bender
