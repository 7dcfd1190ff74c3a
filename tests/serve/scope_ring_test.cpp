// The scope history: bounded whatever the readers do, in order, and a
// reader that waits wakes on the next sample.
#include <gtest/gtest.h>

#include <thread>

#include "tools/serve/scope_ring.hpp"

namespace tnv::serve {
namespace {

ScopeSample at(double t_s) {
  ScopeSample s;
  s.t_s = t_s;
  return s;
}

TEST(ScopeRing, KeepsOnlyItsCapacityWhenNobodyReads) {
  ScopeRing ring(100);
  for (int i = 0; i < 1000; ++i) ring.push(at(i * 0.01));
  EXPECT_EQ(ring.size(), 100u) << "the ring grew past its capacity";
  const std::vector<ScopeSample> all = ring.since(0, 10'000);
  ASSERT_EQ(all.size(), 100u);
  EXPECT_EQ(all.front().seq, 901u) << "the oldest kept sample is not the 100th newest";
  EXPECT_EQ(all.back().seq, 1000u);
  EXPECT_DOUBLE_EQ(all.back().t_s, 9.99);
}

TEST(ScopeRing, GivesOnlyNewerSamplesInOrderUpToTheLimit) {
  ScopeRing ring(50);
  for (int i = 0; i < 20; ++i) ring.push(at(i));
  const std::vector<ScopeSample> newer = ring.since(15, 100);
  ASSERT_EQ(newer.size(), 5u);
  for (std::size_t i = 0; i < newer.size(); ++i) EXPECT_EQ(newer[i].seq, 16u + i);
  EXPECT_EQ(ring.since(0, 3).size(), 3u) << "the limit on one batch was not kept";
  EXPECT_TRUE(ring.since(20, 100).empty()) << "a reader that is up to date got samples again";
}

TEST(ScopeRing, AWaitingReaderWakesOnTheNextSample) {
  ScopeRing ring(10);
  EXPECT_FALSE(ring.wait_newer(0, std::chrono::milliseconds(20))) << "woke with no sample";
  std::thread writer([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ring.push(at(1.0));
  });
  // A wait that missed the push would sleep its whole minute: ending well
  // before it proves the push woke it, on however slow a machine.
  const auto started = std::chrono::steady_clock::now();
  EXPECT_TRUE(ring.wait_newer(0, std::chrono::seconds(60)));
  writer.join();
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(30)) << "the wait did not end on the push";
}

}  // namespace
}  // namespace tnv::serve
