#pragma once
// A deterministic hal::StorageWorker for the in-process HIL rigs: post()
// only remembers the job; the rig calls run_pending() between two ticks,
// outside the time it charges to the board, so a save or load costs the
// real-time loop nothing and a run stays the same from run to run. The
// node sees the job done in its next service().
#include "hal/storage_worker.hpp"

namespace tnv::drivers {

class SteppedStorageWorker final : public hal::StorageWorker {
 public:
  bool post(hal::StorageJob& job) noexcept override {
    if (job_ != nullptr || finished_) return false;
    job_ = &job;
    return true;
  }
  bool done() noexcept override {
    if (!finished_) return false;
    finished_ = false;
    return true;
  }
  // Runs the posted job, if any; true when one ran.
  bool run_pending() noexcept {
    if (job_ == nullptr) return false;
    job_->run();
    job_ = nullptr;
    finished_ = true;
    ++jobs_run_;
    return true;
  }
  bool idle() const noexcept { return job_ == nullptr && !finished_; }
  unsigned long jobs_run() const noexcept { return jobs_run_; }

 private:
  hal::StorageJob* job_ = nullptr;
  bool finished_ = false;
  unsigned long jobs_run_ = 0;
};

}  // namespace tnv::drivers
