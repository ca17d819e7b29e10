#include "FaultInjection.h"

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <cstring>

#include <unistd.h>

namespace bender
{

void FaultPoint(const char* point)
{
  // Read at every call (a few per file written), so that a test may set it in a child process.
  const char* value = std::getenv(FaultInjectionVariable);
  if (!value || !*value)
  {
    return;
  }
  const std::size_t length = std::strlen(point);
  if (std::strncmp(value, point, length) != 0 || (value[length] != '\0' && value[length] != ':'))
  {
    return;
  }
  const long visit = value[length] == ':' ? std::strtol(value + length + 1, nullptr, 10) : 1;
  static std::atomic<long> visits{ 0 };
  if (++visits >= visit)
  {
    ::kill(::getpid(), SIGKILL);
    std::_Exit(137); // not reached: SIGKILL cannot be caught
  }
}

} // namespace bender
