// Shared by the benchmarks (bench/*): one description of the machine a run was taken on and one
// way to summarise repeated timings, so that every benchmark prints the same facts: the CPU
// model, the cores, the SIMD level of the build and of the CPU, and medians with min/max.
//
// Header-only on purpose: the benchmarks are single-file executables that link this through
// the bender_bench_common interface target (bench/CMakeLists.txt).

#ifndef bender_BenchMachine_h
#define bender_BenchMachine_h

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace bender_bench
{

/// What a benchmark's figures depend on, read from /proc/cpuinfo and the compiler.
struct Machine
{
  std::string cpu = "unknown CPU";
  /// Hardware threads the process may use (std::thread::hardware_concurrency).
  unsigned threads = 0;
  /// Physical cores ("cpu cores" of /proc/cpuinfo); 0 when not reported.
  unsigned cores = 0;
  /// Best vector instruction set the CPU reports: "AVX-512", "AVX2", "SSE4.2", "SSE2".
  std::string cpuSimd = "SSE2";
  /// Best vector instruction set the build targets everywhere (compiler flags): code outside
  /// the kernels compiled with run-time dispatch (target_clones) uses at most this.
  std::string buildSimd = "SSE2";
};

/// The level a set of /proc/cpuinfo flags allows.
inline std::string SimdLevelOfFlags(const std::set<std::string>& flags)
{
  if (flags.count("avx512f"))
  {
    return "AVX-512";
  }
  if (flags.count("avx2") && flags.count("fma"))
  {
    return "AVX2";
  }
  if (flags.count("sse4_2"))
  {
    return "SSE4.2";
  }
  return "SSE2";
}

/// The level the compiler was told it may assume (-m flags / -march).
inline std::string BuildSimdLevel()
{
#if defined(__AVX512F__)
  return "AVX-512";
#elif defined(__AVX2__)
  return "AVX2";
#elif defined(__SSE4_2__)
  return "SSE4.2";
#elif defined(__SSE2__)
  return "SSE2";
#else
  return "none (not x86-64)";
#endif
}

inline Machine DescribeMachine()
{
  Machine m;
  m.threads = std::thread::hardware_concurrency();
  m.buildSimd = BuildSimdLevel();
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  bool haveFlags = false;
  while (std::getline(in, line))
  {
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos)
    {
      continue;
    }
    std::string key = line.substr(0, colon);
    key.erase(key.find_last_not_of(" \t") + 1);
    const std::string value = colon + 2 <= line.size() ? line.substr(colon + 2) : std::string();
    if (key == "model name" && m.cpu == "unknown CPU")
    {
      m.cpu = value;
    }
    else if (key == "cpu cores" && m.cores == 0)
    {
      m.cores = static_cast<unsigned>(std::max(0L, std::strtol(value.c_str(), nullptr, 10)));
    }
    else if (key == "flags" && !haveFlags)
    {
      std::istringstream words(value);
      std::set<std::string> flags;
      for (std::string w; words >> w;)
      {
        flags.insert(w);
      }
      m.cpuSimd = SimdLevelOfFlags(flags);
      haveFlags = true;
    }
  }
  return m;
}

/// One line: "machine: <CPU>, <n> cores / <t> hardware threads, SIMD: CPU <level>, build
/// baseline <level> (run-time dispatched kernels up to the CPU's level)".
inline std::string MachineLine()
{
  const Machine m = DescribeMachine();
  std::ostringstream s;
  s << "machine: " << m.cpu << ", ";
  if (m.cores > 0)
  {
    s << m.cores << " cores / ";
  }
  s << m.threads << " hardware threads; SIMD: CPU " << m.cpuSimd << ", build baseline "
    << m.buildSimd << " (kernels dispatched at run time may use the CPU's level)";
  return s.str();
}

/// Median, minimum and maximum of repeated timings.
struct Spread
{
  double median = 0.0;
  double min = 0.0;
  double max = 0.0;
  int runs = 0;
};

/// The median (the mean of the two middle values for an even count), min and max; all zero
/// for no sample.
inline Spread Summarise(std::vector<double> samples)
{
  Spread s;
  s.runs = static_cast<int>(samples.size());
  if (samples.empty())
  {
    return s;
  }
  std::sort(samples.begin(), samples.end());
  const std::size_t n = samples.size();
  s.median = n % 2 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
  s.min = samples.front();
  s.max = samples.back();
  return s;
}

/// "median [min, max]" with `decimals` decimals.
inline std::string Format(const Spread& s, int decimals = 1)
{
  char text[96];
  std::snprintf(
    text, sizeof text, "%.*f [%.*f, %.*f]", decimals, s.median, decimals, s.min, decimals, s.max);
  return text;
}

/// The value below which a fraction `p` (0..1) of `values` lie (the nearest rank); 0 for none.
inline double Percentile(std::vector<double> values, double p)
{
  if (values.empty())
  {
    return 0.0;
  }
  std::sort(values.begin(), values.end());
  const std::size_t i =
    std::min(values.size() - 1, std::size_t(p * double(values.size() - 1) + 0.5));
  return values[i];
}

/// The process's resident set size (VmRSS of /proc/self/status) in MiB; 0 when unknown.
inline double ResidentMiB()
{
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
  {
    if (line.rfind("VmRSS:", 0) == 0)
    {
      return std::strtod(line.c_str() + 6, nullptr) / 1024.0;
    }
  }
  return 0.0;
}

/// Wall-clock milliseconds of `repeats` calls of `run`, one sample per call.
inline std::vector<double> TimeRunsMs(int repeats, const std::function<void()>& run)
{
  std::vector<double> ms;
  for (int i = 0; i < repeats; ++i)
  {
    const auto t0 = std::chrono::steady_clock::now();
    run();
    const auto t1 = std::chrono::steady_clock::now();
    ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
  }
  return ms;
}

} // namespace bender_bench

#endif
