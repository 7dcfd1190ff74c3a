#pragma once
// SIGTERM and SIGINT blocked in the calling thread, and so in every thread
// it starts afterwards (they inherit the mask), to be taken synchronously
// (sigtimedwait, or a signalfd in a poll loop): no handler runs
// concurrently with anything. The daemons call it first thing.
#include <signal.h>

namespace tnv::drivers {

inline sigset_t block_stop_signals() noexcept {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGINT);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  return set;
}

}  // namespace tnv::drivers
