#include "SignalGuard.h"

#include <csignal>

namespace bender
{

namespace
{
std::atomic<bool> SignalFlag{ false };
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");

extern "C" void OnSignal(int)
{
  SignalFlag.store(true);
}
} // namespace

SignalGuard::SignalGuard()
{
  SignalFlag.store(false);
  this->OldInt = std::signal(SIGINT, OnSignal);
  this->OldTerm = std::signal(SIGTERM, OnSignal);
}

SignalGuard::~SignalGuard()
{
  std::signal(SIGINT, this->OldInt);
  std::signal(SIGTERM, this->OldTerm);
}

const std::atomic<bool>* SignalGuard::Flag() const
{
  return &SignalFlag;
}

} // namespace bender
