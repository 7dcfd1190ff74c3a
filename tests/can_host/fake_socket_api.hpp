#pragma once
// A SocketApi that records what the transport asked for and answers from
// scripts: failures per call, reads to return in order, a fake clock that
// poll() advances by its timeout when nothing is pending.
#include <linux/can.h>
#include <poll.h>

#include <cerrno>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "tools/can/socket_api.hpp"

namespace tnv::test {

struct FakeRead {
  can_host::SysResult result;  // value = bytes returned (or -1 with error)
  can_frame frame{};
};

class FakeSocketApi final : public can_host::SocketApi {
 public:
  // --- script
  int fail_index = 0, fail_open = 0, fail_filters = 0, fail_error_mask = 0, fail_nonblocking = 0, fail_bind = 0;
  std::deque<FakeRead> reads;               // empty: EAGAIN
  std::deque<can_host::SysResult> writes;   // empty: success (whole frame)
  bool writable_after_poll = true;          // a POLLOUT poll drains `writes` of EAGAIN/ENOBUFS entries
  bool tx_full = false;                     // every write fails with ENOBUFS

  // --- record
  std::string asked_interface;
  int bound_ifindex = -1;
  std::vector<can_filter> filters;
  can_err_mask_t error_mask = 0;
  bool nonblocking = false;
  int closed = 0;
  std::vector<can_frame> written;
  std::vector<int> poll_timeouts_ms;
  long long now_us = 1'000'000;

  static constexpr int kFd = 7;
  static constexpr int kIfIndex = 3;

  static can_frame frame(canid_t id, std::initializer_list<std::uint8_t> data) {
    can_frame f{};
    f.can_id = id;
    f.can_dlc = static_cast<std::uint8_t>(data.size());
    std::copy(data.begin(), data.end(), f.data);
    return f;
  }
  void queue_frame(const can_frame& f) { reads.push_back({{static_cast<long>(sizeof(can_frame)), 0}, f}); }

  can_host::SysResult interface_index(const std::string& name) override {
    asked_interface = name;
    if (fail_index) return {-1, fail_index};
    return {kIfIndex, 0};
  }
  can_host::SysResult open_can_raw() override {
    if (fail_open) return {-1, fail_open};
    return {kFd, 0};
  }
  can_host::SysResult set_filters(int, std::span<const can_filter> f) override {
    if (fail_filters) return {-1, fail_filters};
    filters.assign(f.begin(), f.end());
    return {0, 0};
  }
  can_host::SysResult set_error_mask(int, can_err_mask_t mask) override {
    if (fail_error_mask) return {-1, fail_error_mask};
    error_mask = mask;
    return {0, 0};
  }
  can_host::SysResult set_nonblocking(int) override {
    if (fail_nonblocking) return {-1, fail_nonblocking};
    nonblocking = true;
    return {0, 0};
  }
  can_host::SysResult bind_can(int, int ifindex) override {
    if (fail_bind) return {-1, fail_bind};
    bound_ifindex = ifindex;
    return {0, 0};
  }
  can_host::SysResult poll_one(int, short events, int timeout_ms) override {
    poll_timeouts_ms.push_back(timeout_ms);
    if ((events & POLLIN) != 0 && !reads.empty() && reads.front().result.error != EAGAIN) return {POLLIN, 0};
    if ((events & POLLOUT) != 0 && writable_after_poll) {
      while (!writes.empty() && writes.front().failed() && writes.front().error != EINTR) writes.pop_front();
      return {POLLOUT, 0};
    }
    now_us += static_cast<long long>(timeout_ms) * 1000;  // nothing happened for the whole timeout
    return {0, 0};
  }
  can_host::SysResult read_some(int, void* buffer, std::size_t size) override {
    if (reads.empty()) return {-1, EAGAIN};
    FakeRead r = reads.front();
    reads.pop_front();
    if (r.result.failed()) return r.result;
    std::memcpy(buffer, &r.frame, std::min<std::size_t>(size, static_cast<std::size_t>(r.result.value)));
    return r.result;
  }
  can_host::SysResult write_some(int, const void* buffer, std::size_t size) override {
    if (tx_full) return {-1, ENOBUFS};
    if (!writes.empty()) {
      const can_host::SysResult r = writes.front();
      writes.pop_front();
      if (r.failed() || r.value != static_cast<long>(size)) return r;
    }
    can_frame f{};
    std::memcpy(&f, buffer, std::min(size, sizeof f));
    written.push_back(f);
    return {static_cast<long>(size), 0};
  }
  void close_fd(int) override { ++closed; }
  can_host::Micros monotonic_now() override { return can_host::Micros{now_us}; }
};

}  // namespace tnv::test
