#ifndef bender_FileSizeLimit_h
#define bender_FileSizeLimit_h

// A full disk, simulated without root: the process's file size limit (RLIMIT_FSIZE) lowered
// for the lifetime of the object. Writes past it fail with EFBIG, as they would with ENOSPC on
// a full disk; SIGXFSZ (which would kill the process) is ignored meanwhile. Programs started
// meanwhile inherit the limit. Used by the volume writers' and the CFD results' full-disk tests.

#include <csignal>

#include <sys/resource.h>

namespace bender::test
{

class FileSizeLimit
{
public:
  explicit FileSizeLimit(rlim_t bytes)
  {
    this->PreviousHandler = std::signal(SIGXFSZ, SIG_IGN);
    ::getrlimit(RLIMIT_FSIZE, &this->Previous);
    rlimit limit = this->Previous;
    limit.rlim_cur = bytes;
    ::setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit()
  {
    ::setrlimit(RLIMIT_FSIZE, &this->Previous);
    std::signal(SIGXFSZ, this->PreviousHandler);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

private:
  rlimit Previous{};
  void (*PreviousHandler)(int) = nullptr;
};

} // namespace bender::test

#endif
