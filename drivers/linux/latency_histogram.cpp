#include "drivers/linux/latency_histogram.hpp"

#include <algorithm>
#include <cstdio>

namespace tnv::drivers {

void LatencyHistogram::record(std::int64_t latency_ns) noexcept {
  const std::int64_t ns = std::max<std::int64_t>(latency_ns, 0);
  const std::size_t bucket = std::min<std::size_t>(static_cast<std::size_t>(ns / 1000), kBuckets);
  // Single writer: plain load/store keeps min and max consistent without CAS loops.
  const std::uint64_t n = count_.load(std::memory_order_relaxed);
  if (n == 0 || ns < min_ns_.load(std::memory_order_relaxed)) min_ns_.store(ns, std::memory_order_relaxed);
  if (n == 0 || ns > max_ns_.load(std::memory_order_relaxed)) max_ns_.store(ns, std::memory_order_relaxed);
  sum_ns_.fetch_add(ns, std::memory_order_relaxed);
  buckets_[bucket].fetch_add(1, std::memory_order_relaxed);
  count_.store(n + 1, std::memory_order_release);
}

LatencySummary LatencyHistogram::snapshot() const {
  LatencySummary s;
  s.count = count_.load(std::memory_order_acquire);
  s.min_ns = min_ns_.load(std::memory_order_relaxed);
  s.max_ns = max_ns_.load(std::memory_order_relaxed);
  const std::int64_t sum = sum_ns_.load(std::memory_order_relaxed);
  s.mean_ns = s.count == 0 ? 0.0 : static_cast<double>(sum) / static_cast<double>(s.count);
  s.buckets.resize(kBuckets + 1);
  for (std::size_t i = 0; i <= kBuckets; ++i) s.buckets[i] = buckets_[i].load(std::memory_order_relaxed);
  return s;
}

std::int64_t LatencySummary::percentile_us(double p) const noexcept {
  std::uint64_t total = 0;
  for (const std::uint64_t b : buckets) total += b;
  if (total == 0) return 0;
  const auto rank = static_cast<std::uint64_t>(p / 100.0 * static_cast<double>(total) + 0.999999);
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < buckets.size(); ++i) {
    seen += buckets[i];
    if (seen >= std::max<std::uint64_t>(rank, 1)) return static_cast<std::int64_t>(i + 1);
  }
  return static_cast<std::int64_t>(buckets.size());
}

std::string LatencySummary::one_line() const {
  char line[160];
  std::snprintf(line, sizeof line, "min %lld us  avg %.1f us  p99 %lld us  max %lld us  (n = %llu)",
                static_cast<long long>(min_ns / 1000), mean_ns / 1000.0, static_cast<long long>(percentile_us(99.0)),
                static_cast<long long>(max_ns / 1000), static_cast<unsigned long long>(count));
  return line;
}

std::string LatencySummary::histogram_text() const {
  std::string out = one_line();
  out += '\n';
  for (std::size_t i = 0; i < buckets.size(); ++i) {
    if (buckets[i] == 0) continue;
    char line[64];
    if (i + 1 == buckets.size()) {
      std::snprintf(line, sizeof line, "  >=%zu us: %llu\n", i, static_cast<unsigned long long>(buckets[i]));
    } else {
      std::snprintf(line, sizeof line, "  %4zu us: %llu\n", i, static_cast<unsigned long long>(buckets[i]));
    }
    out += line;
  }
  return out;
}

}  // namespace tnv::drivers
