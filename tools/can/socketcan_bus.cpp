#include "tools/can/socketcan_bus.hpp"

#include <linux/can/error.h>
#include <poll.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "firmware/can/can_id.hpp"

namespace tnv::can_host {

can_filter node_filter(std::uint8_t node) noexcept {
  can_filter f{};
  f.can_id = node & fw::can::kNodeIdMask;
  // Match the node bits, and require the EFF and RTR flags to be clear.
  f.can_mask = fw::can::kNodeIdMask | CAN_EFF_FLAG | CAN_RTR_FLAG;
  return f;
}

SocketCanBus::SocketCanBus(SocketApi& api, const SocketCanOptions& options) : api_(api), options_(options) {
  const SysResult index = api_.interface_index(options_.interface_name);
  if (index.failed()) fail("no such network interface", index.error);
  const SysResult fd = api_.open_can_raw();
  if (fd.failed()) fail("cannot open a CAN_RAW socket", fd.error);
  fd_ = static_cast<int>(fd.value);
  const can_filter filter = node_filter(options_.node);
  if (const SysResult r = api_.set_filters(fd_, {&filter, 1}); r.failed()) fail("cannot set the receive filter", r.error);
  const can_err_mask_t errors = CAN_ERR_MASK;
  if (const SysResult r = api_.set_error_mask(fd_, errors); r.failed()) fail("cannot enable error frames", r.error);
  if (const SysResult r = api_.set_nonblocking(fd_); r.failed()) fail("cannot make the socket non-blocking", r.error);
  if (const SysResult r = api_.bind_can(fd_, static_cast<int>(index.value)); r.failed())
    fail(bind_failure(options_.interface_name, r.error), r.error);
}

// What a failed bind means: on a CAN interface, usually that it is down;
// on tnv-fw's `unix:` socket, that the node is not there or that its
// owner-only socket (0600, docs/safety.md) refused another user.
const char* SocketCanBus::bind_failure(const std::string& interface_name, int error) noexcept {
  if (interface_name.rfind("unix:", 0) != 0) return "cannot bind (is the interface up? ip link set can0 up type can bitrate 1000000)";
  if (error == EACCES || error == EPERM)
    return "refused: the node's socket is owner-only (tnv-fw makes it 0600); connect as the user that runs tnv-fw";
  if (error == ENOENT || error == ECONNREFUSED) return "no node listening there (is tnv-fw running with this socket?)";
  return "cannot connect to the node's socket";
}

SocketCanBus::~SocketCanBus() {
  if (fd_ >= 0) api_.close_fd(fd_);
}

void SocketCanBus::fail(const char* step, int error) const {
  std::string message = options_.interface_name;
  message.append(": ").append(step);
  if (error != 0) message.append(": ").append(std::strerror(error));
  if (fd_ >= 0) api_.close_fd(fd_);
  throw BusError(message);
}

int SocketCanBus::wait_ms(Micros deadline) {
  const Micros left = deadline - api_.monotonic_now();
  if (left <= Micros{0}) return 0;
  return static_cast<int>(std::min<long long>((left.count() + 999) / 1000, 60'000));
}

void SocketCanBus::send(const hal::CanFrame& frame) {
  can_frame raw{};
  raw.can_id = frame.extended ? ((frame.id & CAN_EFF_MASK) | CAN_EFF_FLAG) : (frame.id & CAN_SFF_MASK);
  raw.can_dlc = std::min<std::uint8_t>(frame.dlc, 8);
  std::copy(frame.data.begin(), frame.data.end(), raw.data);
  const Micros deadline = api_.monotonic_now() + options_.send_timeout;
  for (;;) {
    const SysResult w = api_.write_some(fd_, &raw, sizeof raw);
    if (!w.failed()) {
      if (w.value != static_cast<long>(sizeof raw)) {
        std::string message = options_.interface_name;
        message += ": short write of a CAN frame";
        throw BusError(message);
      }
      ++counters_.tx_frames;
      return;
    }
    if (w.error == EINTR) continue;
    // A full transmit queue: wait for room, up to the send timeout.
    if (w.error != EAGAIN && w.error != EWOULDBLOCK && w.error != ENOBUFS) {
      std::string message = options_.interface_name;
      message.append(": send failed: ").append(std::strerror(w.error));
      throw BusError(message);
    }
    const int ms = wait_ms(deadline);
    if (ms == 0) {
      std::string message = options_.interface_name;
      message += ": transmit queue full (no ack on the bus? is a node connected and the bit rate right?)";
      throw BusError(message);
    }
    const SysResult p = api_.poll_one(fd_, POLLOUT, ms);
    if (p.failed() && p.error != EINTR) {
      std::string message = options_.interface_name;
      message.append(": poll failed: ").append(std::strerror(p.error));
      throw BusError(message);
    }
  }
}

std::optional<hal::CanFrame> SocketCanBus::receive(Micros timeout) {
  const Micros deadline = api_.monotonic_now() + timeout;
  bool error_seen = false;
  for (;;) {
    can_frame raw{};
    const SysResult r = api_.read_some(fd_, &raw, sizeof raw);
    if (!r.failed()) {
      if (r.value != static_cast<long>(sizeof raw)) {
        ++counters_.rx_short_reads;  // not a whole frame: discard it
        continue;
      }
      if ((raw.can_id & CAN_ERR_FLAG) != 0) {
        ++counters_.rx_error_frames;
        last_error_class_ = raw.can_id & CAN_ERR_MASK;
        continue;
      }
      if ((raw.can_id & CAN_RTR_FLAG) != 0) continue;
      hal::CanFrame frame;
      frame.extended = (raw.can_id & CAN_EFF_FLAG) != 0;
      frame.id = raw.can_id & (frame.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
      frame.dlc = std::min<std::uint8_t>(raw.can_dlc, 8);
      std::copy(raw.data, raw.data + 8, frame.data.begin());
      ++counters_.rx_frames;
      return frame;
    }
    if (r.error == EINTR) continue;
    if (r.error != EAGAIN && r.error != EWOULDBLOCK) {
      std::string message = options_.interface_name;
      message.append(": receive failed: ").append(std::strerror(r.error));
      throw BusError(message);
    }
    const int ms = wait_ms(deadline);
    if (ms == 0) return std::nullopt;
    const SysResult p = api_.poll_one(fd_, POLLIN, ms);
    if (p.failed()) {
      if (p.error == EINTR) return std::nullopt;  // a signal (Ctrl-C): let the caller look
      std::string message = options_.interface_name;
      message.append(": poll failed: ").append(std::strerror(p.error));
      throw BusError(message);
    }
    // POLLERR: the next read reports the socket error; a second one with
    // nothing to read means the error is not going away.
    const bool error_pending = (p.value & POLLERR) != 0;
    if ((p.value & (POLLHUP | POLLNVAL)) != 0 || (error_pending && error_seen)) {
      std::string message = options_.interface_name;
      message += ": the interface went away or reported an error";
      throw BusError(message);
    }
    error_seen = error_pending;
  }
}

}  // namespace tnv::can_host
