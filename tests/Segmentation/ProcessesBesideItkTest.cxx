// Programs started from two threads at once in a process whose ITK thread pool has threads.
// ITK 5.2's fork handlers stop the pool's threads before every fork and start new ones after
// it, and are not safe against a fork on another thread: a Flow run of both shapes at once after
// the demo's segmentation hung in them. RunProcess forks one at a time.

#include "ProcessRunner.h"

#include <itkMultiThreaderBase.h>

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

TEST(ProcessesBesideItk, ProgramsStartedFromTwoThreadsAtOnceAllFinish)
{
  // The pool at work, as after a segmentation.
  itk::MultiThreaderBase::Pointer threader = itk::MultiThreaderBase::New();
  threader->SetNumberOfWorkUnits(8);
  std::atomic<int> done{ 0 };
  threader->ParallelizeArray(
    0, 1000, [&done](itk::SizeValueType) { ++done; }, nullptr);
  ASSERT_EQ(done.load(), 1000);

  std::atomic<int> succeeded{ 0 };
  const auto start = [&succeeded]()
  {
    for (int i = 0; i < 40; ++i)
    {
      bender::ProcessOptions options;
      options.argv = { "true" };
      succeeded += bender::RunProcess(options).Succeeded() ? 1 : 0;
    }
  };
  std::thread other(start);
  start();
  other.join();
  EXPECT_EQ(succeeded.load(), 80);
  // The pool still works after the forks.
  done = 0;
  threader->ParallelizeArray(
    0, 1000, [&done](itk::SizeValueType) { ++done; }, nullptr);
  EXPECT_EQ(done.load(), 1000);
}
