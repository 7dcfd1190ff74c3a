#pragma once
// Every system call a SocketCAN transport makes, behind one small
// interface, so unit tests drive the transport with a fake socket (no
// kernel CAN needed). Results carry the errno instead of relying on the
// global, which keeps fakes honest. Used by the firmware's CAN port
// (socketcan_port.hpp) and by the host's bus (tools/can/socketcan_bus.hpp).
#include <linux/can.h>

#include <cerrno>
#include <chrono>
#include <cstddef>
#include <span>
#include <string>

namespace tnv::drivers {

using Micros = std::chrono::microseconds;

struct SysResult {
  long value = 0;  // the call's return value; -1 on failure
  int error = 0;   // errno when value == -1
  bool failed() const noexcept { return value < 0; }
};

// A system call's return value with errno captured right after it.
inline SysResult result_of(long value) noexcept { return {value, value < 0 ? errno : 0}; }

class SocketApi {
 public:
  virtual ~SocketApi() = default;
  virtual SysResult open_can_raw() = 0;                        // socket(PF_CAN, SOCK_RAW, CAN_RAW)
  virtual SysResult interface_index(const std::string& name) = 0;  // if_nametoindex
  virtual SysResult set_filters(int fd, std::span<const can_filter> filters) = 0;  // CAN_RAW_FILTER
  virtual SysResult set_error_mask(int fd, can_err_mask_t mask) = 0;               // CAN_RAW_ERR_FILTER
  virtual SysResult set_nonblocking(int fd) = 0;
  // SO_SNDBUF (the kernel rounds up to its minimum). Default: not supported, nothing done.
  virtual SysResult set_send_buffer(int /*fd*/, int /*bytes*/) { return {}; }
  virtual SysResult bind_can(int fd, int ifindex) = 0;
  // poll() on one descriptor; value = revents (0 on timeout).
  virtual SysResult poll_one(int fd, short events, int timeout_ms) = 0;
  virtual SysResult read_some(int fd, void* buffer, std::size_t size) = 0;
  virtual SysResult write_some(int fd, const void* buffer, std::size_t size) = 0;
  virtual void close_fd(int fd) = 0;
  virtual Micros monotonic_now() = 0;
};

// The real one (Linux system calls, steady clock).
SocketApi& linux_socket_api();

}  // namespace tnv::drivers
