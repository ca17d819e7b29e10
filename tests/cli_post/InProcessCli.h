#ifndef bender_InProcessCli_h
#define bender_InProcessCli_h

// Runs a bender-cli command in-process (the command library) and captures what it prints.

#include "CliCommands.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace bendertest
{
struct CliRun
{
  int status = -1;
  std::string out;
  std::string err;
};

inline CliRun RunInProcess(const std::vector<std::string>& args)
{
  CliRun c;
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  c.status = bender::RunBenderCli(args);
  std::cout.flush();
  std::cerr.flush();
  std::fflush(stdout);
  std::fflush(stderr);
  c.out = ::testing::internal::GetCapturedStdout();
  c.err = ::testing::internal::GetCapturedStderr();
  return c;
}
} // namespace bendertest

#endif
