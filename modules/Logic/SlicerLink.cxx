#include "SlicerLink.h"

#include "BenderErrors.h"
#include "IgtlSurfaceFromMesh.h"
#include "TrackingErrors.h"

#include <algorithm>
#include <chrono>
#include <exception>

namespace bender
{

std::shared_ptr<SlicerLink::Frame> SlicerLink::MakeFrame(vtkPolyData* surface,
  const std::string& name,
  const std::optional<RibbonSpec>& ribbon,
  bool final)
{
  auto frame = std::make_shared<Frame>();
  frame->surface = MakeIgtlSurface(surface, name);
  frame->final = final;
  if (ribbon)
  {
    try
    {
      IgtlRibbonEndFrame(ribbon->start);
      IgtlRibbonEndFrame(ribbon->end);
      frame->ribbon = ribbon;
    }
    catch (const TrackingError&)
    {
      // A degenerate end frame (zero tangent, normal along it) is not sent; the surface is.
    }
  }
  return frame;
}

SlicerLink::SlicerLink(Options options, std::function<void(std::string)> onError)
  : Opts(std::move(options))
  , OnError(std::move(onError))
{
  this->Thread = std::thread([this]() { this->Loop(); });
}

SlicerLink::~SlicerLink()
{
  this->RequestStop();
  if (this->Thread.joinable())
  {
    this->Thread.join();
  }
}

void SlicerLink::RequestStop()
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  this->StopRequested = true;
  this->Wake.notify_all();
}

void SlicerLink::Submit(std::shared_ptr<Frame> frame)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  if (this->Pending && this->Pending->final)
  {
    frame->final = true;
  }
  this->Pending = std::move(frame);
  this->Wake.notify_all();
}

void SlicerLink::Finish()
{
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    this->Wake.wait(lock, [this]() { return !this->Pending || this->Done.load(); });
  }
  this->RequestStop();
  if (this->Thread.joinable())
  {
    this->Thread.join();
  }
  if (!this->Failure.empty())
  {
    throw Error(this->Failure);
  }
}

SlicerLink::Counters SlicerLink::GetCounters() const
{
  Counters counters;
  counters.connected = this->Connected.load();
  counters.messages = this->Messages.load();
  counters.bytes = this->Bytes.load();
  counters.surfaces = this->Surfaces.load();
  return counters;
}

void SlicerLink::Loop()
{
  std::string failure;
  try
  {
    IgtlSender sender(this->Opts.sender);
    sender.Connect();
    this->Connected = true;
    std::unique_lock<std::mutex> lock(this->Mutex);
    for (;;)
    {
      this->Wake.wait(lock, [this]() { return this->StopRequested || this->Pending; });
      if (this->StopRequested)
      {
        break;
      }
      const std::shared_ptr<Frame> frame = this->Pending;
      lock.unlock();
      bool sent = true;
      if (frame->final)
      {
        sender.SendSurface(frame->surface, this->Opts.surfaceName);
      }
      else
      {
        sent = sender.SendSurfaceIfDue(frame->surface, this->Opts.surfaceName);
      }
      if (sent && frame->ribbon)
      {
        sender.SendRibbonEnds(*frame->ribbon, this->Opts.ribbonPrefix);
      }
      this->Messages = sender.MessagesSent();
      this->Bytes = sender.BytesSent();
      lock.lock();
      if (sent)
      {
        ++this->Surfaces;
        if (this->Pending == frame)
        {
          this->Pending.reset();
          this->Wake.notify_all(); // Finish waits for this
        }
      }
      else
      {
        // A quarter of the interval between live surfaces.
        const double rate = std::max(this->Opts.sender.maxSurfaceRateHz, 1.0);
        this->Wake.wait_for(lock,
          std::chrono::milliseconds(int(1000.0 / rate) / 4 + 1),
          [this, &frame]() { return this->StopRequested || this->Pending != frame; });
      }
    }
  }
  catch (const std::exception& e) // nothing leaves the thread: TransportError, std::system_error
  {
    failure = e.what();
  }
  this->Connected = false;
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->Failure = failure;
    this->Done = true;
    this->Wake.notify_all();
  }
  if (!failure.empty() && this->OnError)
  {
    this->OnError(failure);
  }
}

} // namespace bender
