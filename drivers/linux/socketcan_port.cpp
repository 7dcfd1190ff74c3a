#include "drivers/linux/socketcan_port.hpp"

#include <linux/can/error.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace tnv::drivers {

namespace {

can_filter filter_for(std::uint8_t node) noexcept {
  can_filter f{};
  // The node id is the identifier's low 5 bits (firmware/can/can_id.hpp).
  f.can_id = node & 0x1Fu;
  // Match the node bits and require the EFF and RTR flags to be clear.
  f.can_mask = 0x1Fu | CAN_EFF_FLAG | CAN_RTR_FLAG;
  return f;
}

std::string step_error(const std::string& interface_name, const char* step, int error) {
  std::string message = interface_name;
  message.append(": ").append(step);
  if (error != 0) message.append(": ").append(std::strerror(error));
  return message;
}

}  // namespace

NodeFilters node_filters(std::uint8_t node) noexcept { return {filter_for(node), filter_for(0)}; }

std::unique_ptr<SocketCanPort> SocketCanPort::open(SocketApi& api, const SocketCanPortOptions& options,
                                                   std::string& error) {
  const SysResult index = api.interface_index(options.interface_name);
  if (index.failed()) {
    error = step_error(options.interface_name, "no such network interface", index.error);
    return nullptr;
  }
  const SysResult opened = api.open_can_raw();
  if (opened.failed()) {
    error = step_error(options.interface_name, "cannot open a CAN_RAW socket", opened.error);
    return nullptr;
  }
  const int fd = static_cast<int>(opened.value);
  auto fail = [&](const char* step, int e) {
    error = step_error(options.interface_name, step, e);
    api.close_fd(fd);
    return nullptr;
  };
  const NodeFilters filters = node_filters(options.node_id);
  const can_filter both[2] = {filters.node, filters.broadcast};
  if (const SysResult r = api.set_filters(fd, both); r.failed()) return fail("cannot set the receive filters", r.error);
  // Every error class: bus-off and restarts drive the recovery, the rest is counted.
  if (const SysResult r = api.set_error_mask(fd, CAN_ERR_MASK); r.failed())
    return fail("cannot enable error frames", r.error);
  // The kernel's transmit path is first come, first served: keep what waits
  // there short (the smallest send buffer the kernel allows, a few frames)
  // so that the node's own priority queue decides what goes out next and a
  // FAULT_EVENT or a reply never waits behind a backlog of telemetry.
  if (const SysResult r = api.set_send_buffer(fd, kSendBufferBytes); r.failed())
    return fail("cannot shorten the socket's send buffer", r.error);
  if (const SysResult r = api.set_nonblocking(fd); r.failed())
    return fail("cannot make the socket non-blocking", r.error);
  if (const SysResult r = api.bind_can(fd, static_cast<int>(index.value)); r.failed())
    return fail("cannot bind (is the interface up?)", r.error);
  return std::unique_ptr<SocketCanPort>(new SocketCanPort(api, options, fd));
}

SocketCanPort::SocketCanPort(SocketApi& api, const SocketCanPortOptions& options, int fd) noexcept
    : api_(api), options_(options), fd_(fd) {}

SocketCanPort::~SocketCanPort() { api_.close_fd(fd_); }

hal::HalStatus SocketCanPort::try_send(const hal::CanFrame& frame) noexcept {
  if (bus_off_.load(std::memory_order_relaxed)) {
    // Quiet for the hold-off, then let one frame probe the controller.
    if (api_.monotonic_now() - bus_off_since_ < options_.bus_off_holdoff) {
      add(tx_dropped_);
      return hal::HalStatus::timeout;
    }
  }
  can_frame raw{};
  raw.can_id = frame.extended ? ((frame.id & CAN_EFF_MASK) | CAN_EFF_FLAG) : (frame.id & CAN_SFF_MASK);
  raw.can_dlc = std::min<std::uint8_t>(frame.dlc, 8);
  std::copy(frame.data.begin(), frame.data.end(), raw.data);
  const SysResult w = api_.write_some(fd_, &raw, sizeof raw);
  if (!w.failed() && w.value == static_cast<long>(sizeof raw)) {
    add(tx_frames_);
    if (bus_off_.exchange(false, std::memory_order_relaxed)) add(bus_off_recoveries_);
    return hal::HalStatus::ok;
  }
  add(tx_dropped_);
  if (bus_off_.load(std::memory_order_relaxed)) bus_off_since_ = api_.monotonic_now();  // probe failed: wait again
  if (w.failed() && (w.error == EAGAIN || w.error == EWOULDBLOCK || w.error == ENOBUFS)) return hal::HalStatus::timeout;
  return hal::HalStatus::bus_error;
}

void SocketCanPort::on_error_frame(const can_frame& raw) noexcept {
  add(rx_error_frames_);
  if ((raw.can_id & CAN_ERR_BUSOFF) != 0) {
    if (!bus_off_.exchange(true, std::memory_order_relaxed)) add(bus_off_events_);
    bus_off_since_ = api_.monotonic_now();
  }
  if ((raw.can_id & CAN_ERR_RESTARTED) != 0 && bus_off_.exchange(false, std::memory_order_relaxed)) {
    add(bus_off_recoveries_);
  }
  if ((raw.can_id & CAN_ERR_CRTL) != 0 && (raw.data[1] & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) != 0) {
    add(error_passive_events_);
  }
}

bool SocketCanPort::try_receive(hal::CanFrame& frame) noexcept {
  for (int i = 0; i < options_.max_reads_per_receive; ++i) {
    can_frame raw{};
    const SysResult r = api_.read_some(fd_, &raw, sizeof raw);
    if (r.failed()) {
      if (r.error != EAGAIN && r.error != EWOULDBLOCK && r.error != EINTR) add(rx_failures_);
      return false;
    }
    if (r.value != static_cast<long>(sizeof raw)) {
      add(rx_short_reads_);
      continue;
    }
    if ((raw.can_id & CAN_ERR_FLAG) != 0) {
      on_error_frame(raw);
      continue;
    }
    if ((raw.can_id & CAN_RTR_FLAG) != 0) continue;
    frame.extended = (raw.can_id & CAN_EFF_FLAG) != 0;
    frame.id = raw.can_id & (frame.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
    frame.dlc = std::min<std::uint8_t>(raw.can_dlc, 8);
    std::copy(raw.data, raw.data + 8, frame.data.begin());
    add(rx_frames_);
    return true;
  }
  return false;
}

CanPortCounters SocketCanPort::counters() const noexcept {
  auto get = [](const std::atomic<std::uint64_t>& c) { return c.load(std::memory_order_relaxed); };
  CanPortCounters c;
  c.rx_frames = get(rx_frames_);
  c.rx_error_frames = get(rx_error_frames_);
  c.rx_short_reads = get(rx_short_reads_);
  c.rx_failures = get(rx_failures_);
  c.tx_frames = get(tx_frames_);
  c.tx_dropped = get(tx_dropped_);
  c.bus_off_events = get(bus_off_events_);
  c.bus_off_recoveries = get(bus_off_recoveries_);
  c.error_passive_events = get(error_passive_events_);
  return c;
}

}  // namespace tnv::drivers
