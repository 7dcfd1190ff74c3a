// The storage workers that run save/load off the real-time thread: one job
// at a time, done() reports it once, a second post while busy is refused.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "drivers/storage/stepped_storage_worker.hpp"
#include "drivers/storage/thread_storage_worker.hpp"

namespace tnv::test {
namespace {

class CountingStorageJob final : public hal::StorageJob {
 public:
  void run() noexcept override {
    started = true;
    while (hold.load()) std::this_thread::yield();
    ran_on = std::this_thread::get_id();
    ++runs;
  }
  std::atomic<bool> hold{false};
  std::atomic<bool> started{false};
  std::thread::id ran_on{};
  int runs = 0;
};

// Polls done() as the real-time loop would, once per ms, for up to 5 s.
bool wait_storage_job_done(hal::StorageWorker& w) {
  for (int k = 0; k < 5000; ++k) {
    if (w.done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

TEST(ThreadStorageWorker, RunsTheJobOnItsOwnThreadAndReportsItDoneOnce) {
  drivers::ThreadStorageWorker worker(std::chrono::microseconds(200));
  CountingStorageJob job;
  job.hold = true;
  EXPECT_FALSE(worker.done()) << "nothing posted";
  ASSERT_TRUE(worker.post(job));
  CountingStorageJob other;
  EXPECT_FALSE(worker.post(other)) << "one job at a time";
  EXPECT_FALSE(worker.done()) << "still running";
  job.hold = false;
  ASSERT_TRUE(wait_storage_job_done(worker));
  EXPECT_EQ(job.runs, 1);
  EXPECT_NE(job.ran_on, std::this_thread::get_id());
  EXPECT_FALSE(worker.done()) << "reported once";
  ASSERT_TRUE(worker.post(other)) << "free again after done()";
  ASSERT_TRUE(wait_storage_job_done(worker));
  EXPECT_EQ(other.runs, 1);
}

TEST(ThreadStorageWorker, DestructionWaitsForARunningJob) {
  CountingStorageJob job;
  std::thread release;
  {
    drivers::ThreadStorageWorker worker(std::chrono::microseconds(200));
    job.hold = true;
    ASSERT_TRUE(worker.post(job));
    for (int k = 0; k < 5000 && !job.started; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    ASSERT_TRUE(job.started);
    release = std::thread([&job] {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      job.hold = false;
    });
  }  // the destructor joins the worker, which finishes the job first
  EXPECT_EQ(job.runs, 1);
  release.join();
}

TEST(SteppedStorageWorker, RunsOnlyWhenTheRigStepsIt) {
  drivers::SteppedStorageWorker worker;
  CountingStorageJob job;
  EXPECT_TRUE(worker.idle());
  EXPECT_FALSE(worker.run_pending());
  ASSERT_TRUE(worker.post(job));
  EXPECT_FALSE(worker.post(job));
  EXPECT_FALSE(worker.done());
  EXPECT_EQ(job.runs, 0);
  EXPECT_TRUE(worker.run_pending());
  EXPECT_EQ(job.runs, 1);
  EXPECT_EQ(job.ran_on, std::this_thread::get_id());
  EXPECT_FALSE(worker.post(job)) << "not collected yet";
  EXPECT_TRUE(worker.done());
  EXPECT_FALSE(worker.done());
  EXPECT_TRUE(worker.idle());
  EXPECT_EQ(worker.jobs_run(), 1u);
}

}  // namespace
}  // namespace tnv::test
