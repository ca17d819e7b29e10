#include "TrackerDevice.h"

namespace bender
{

bool TrackerDevice::ReaderRunning()
{
  if (this->Reader.joinable())
  {
    if (this->Streaming.load())
    {
      return true;
    }
    this->Reader.join();
  }
  return false;
}

void TrackerDevice::StartReader(std::function<void()> loop)
{
  this->StopFlag = false;
  this->Store.Rearm();
  this->ReaderStart = std::chrono::steady_clock::now();
  this->Streaming = true;
  this->Reader = std::thread(std::move(loop));
}

void TrackerDevice::StopReader()
{
  this->StopFlag = true;
  this->Store.Cancel();
  if (this->Reader.joinable())
  {
    this->Reader.join();
  }
  this->Streaming = false;
}

double TrackerDevice::ReaderTime() const
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->ReaderStart)
    .count();
}

} // namespace bender
