#pragma once
// hal::StorageWorker on its own (normal-priority) thread, for tnv-fw: the
// real-time loop posts a job with one atomic store and polls with one
// atomic load (no lock, no system call on its side); the worker thread
// polls for work every `poll_period` and runs the job (file I/O, fsync).
// A save therefore answers within about one poll period plus the I/O.
#include <atomic>
#include <chrono>
#include <thread>

#include "hal/storage_worker.hpp"

namespace tnv::drivers {

class ThreadStorageWorker final : public hal::StorageWorker {
 public:
  explicit ThreadStorageWorker(std::chrono::microseconds poll_period = std::chrono::milliseconds(2));
  ~ThreadStorageWorker() override;  // joins; a job in run() finishes first
  ThreadStorageWorker(const ThreadStorageWorker&) = delete;
  ThreadStorageWorker& operator=(const ThreadStorageWorker&) = delete;

  bool post(hal::StorageJob& job) noexcept override;
  bool done() noexcept override;

 private:
  enum State : int { kIdle, kPosted, kDone };
  void loop(const std::stop_token& stop);

  std::chrono::microseconds poll_period_;
  std::atomic<int> state_{kIdle};
  hal::StorageJob* job_ = nullptr;  // written before kPosted is published, read after
  std::jthread thread_;
};

}  // namespace tnv::drivers
