#include "drivers/storage/thread_storage_worker.hpp"

namespace tnv::drivers {

ThreadStorageWorker::ThreadStorageWorker(std::chrono::microseconds poll_period)
    : poll_period_(poll_period), thread_([this](const std::stop_token& stop) { loop(stop); }) {}

ThreadStorageWorker::~ThreadStorageWorker() {
  thread_.request_stop();
  if (thread_.joinable()) thread_.join();
}

bool ThreadStorageWorker::post(hal::StorageJob& job) noexcept {
  if (state_.load(std::memory_order_acquire) != kIdle) return false;
  job_ = &job;
  state_.store(kPosted, std::memory_order_release);
  return true;
}

bool ThreadStorageWorker::done() noexcept {
  if (state_.load(std::memory_order_acquire) != kDone) return false;
  job_ = nullptr;
  state_.store(kIdle, std::memory_order_release);
  return true;
}

void ThreadStorageWorker::loop(const std::stop_token& stop) {
  while (!stop.stop_requested()) {
    if (state_.load(std::memory_order_acquire) == kPosted) {
      job_->run();
      state_.store(kDone, std::memory_order_release);
      continue;
    }
    std::this_thread::sleep_for(poll_period_);
  }
}

}  // namespace tnv::drivers
