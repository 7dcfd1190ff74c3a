#pragma once
// A SocketApi that carries struct can_frame over a Unix datagram socket
// instead of a CAN interface: a two-party "bus" for rigs without SocketCAN
// (containers whose kernel has no vcan). Not for a machine: no
// arbitration, no error frames from a controller (the peer may send them).
//
// The node side binds `path` and answers whoever wrote to it last; the
// host side binds an abstract autobound address, connects to `path` and
// sends one empty datagram so the node knows where to send from then on.
// Filters and the error mask are applied here as CAN_RAW applies them in
// the kernel. With no peer yet, writes fail with ENOBUFS, as an unacked
// CAN transmit queue fills up. One socket per instance.
#include <sys/socket.h>
#include <sys/un.h>

#include <string>
#include <vector>

#include "drivers/linux/socket_api.hpp"

namespace tnv::drivers {

class UnixCanSocketApi final : public SocketApi {
 public:
  enum class Role : std::uint8_t { node, host };
  UnixCanSocketApi(std::string path, Role role) : path_(std::move(path)), role_(role) {}

  SysResult open_can_raw() override;
  SysResult interface_index(const std::string& name) override;
  SysResult set_filters(int fd, std::span<const can_filter> filters) override;
  SysResult set_error_mask(int fd, can_err_mask_t mask) override;
  SysResult set_nonblocking(int fd) override;
  SysResult bind_can(int fd, int ifindex) override;
  SysResult poll_one(int fd, short events, int timeout_ms) override;
  SysResult read_some(int fd, void* buffer, std::size_t size) override;
  SysResult write_some(int fd, const void* buffer, std::size_t size) override;
  void close_fd(int fd) override;
  Micros monotonic_now() override;

 private:
  bool passes(const can_frame& f) const noexcept;

  std::string path_;
  Role role_;
  std::vector<can_filter> filters_{can_filter{0, 0}};  // CAN_RAW's default: everything
  can_err_mask_t error_mask_ = 0;
  sockaddr_un peer_{};
  socklen_t peer_len_ = 0;
};

// "unix:/run/tnv/can.sock" -> "/run/tnv/can.sock"; "" for a real interface name.
std::string unix_can_path(const std::string& interface_name);

}  // namespace tnv::drivers
