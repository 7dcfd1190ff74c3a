#include "tools/can/virtual_can_bus.hpp"

#include <algorithm>

namespace tnv::can_host {

VirtualCanBus::VirtualCanBus(const VirtualCanBusOptions& options) : options_(options) {}

std::uint32_t VirtualCanBus::frame_bits(const hal::CanFrame& frame) noexcept {
  // SOF, arbitration, control, CRC, ack, EOF and 3 bits of interframe space:
  // 47 bits for an 11-bit identifier, 67 for a 29-bit one.
  const std::uint32_t overhead = frame.extended ? 67u : 47u;
  return overhead + 8u * std::min<std::uint32_t>(frame.dlc, 8u);
}

Micros VirtualCanBus::duration(const hal::CanFrame& frame) const noexcept {
  const std::uint64_t ns = static_cast<std::uint64_t>(frame_bits(frame)) * 1'000'000'000ull / options_.bitrate_bit_s;
  return Micros{static_cast<Micros::rep>((ns + 999) / 1000)};
}

bool VirtualCanBus::enqueue(BusSide from, const hal::CanFrame& frame, Micros now) {
  auto& queue = tx_[index(from)];
  if (from == BusSide::node && queue.size() >= options_.node_tx_capacity) return false;
  queue.push_back({frame, now});
  return true;
}

void VirtualCanBus::advance_to(Micros until) {
  for (;;) {
    auto& host = tx_[index(BusSide::host)];
    auto& node = tx_[index(BusSide::node)];
    if (host.empty() && node.empty()) return;
    // The bus goes idle at bus_free_at_; the first frame queued decides when
    // arbitration starts, and every frame queued by then competes.
    Micros earliest = Micros::max();
    if (!host.empty()) earliest = std::min(earliest, host.front().queued);
    if (!node.empty()) earliest = std::min(earliest, node.front().queued);
    const Micros start = std::max(bus_free_at_, earliest);
    const bool host_ready = !host.empty() && host.front().queued <= start;
    const bool node_ready = !node.empty() && node.front().queued <= start;
    BusSide from = host_ready ? BusSide::host : BusSide::node;  // at least one is ready
    if (host_ready && node_ready) from = node.front().frame.id < host.front().frame.id ? BusSide::node : BusSide::host;
    auto& queue = tx_[index(from)];
    const Micros end = start + duration(queue.front().frame);
    if (end > until) return;
    const hal::CanFrame frame = queue.front().frame;
    queue.pop_front();
    bus_free_at_ = end;
    counters_.busy_bits += frame_bits(frame);
    const BusSide to = from == BusSide::host ? BusSide::node : BusSide::host;
    auto& inbox = rx_[index(to)];
    const std::size_t capacity = to == BusSide::host ? options_.host_rx_capacity : options_.node_rx_capacity;
    if (inbox.size() >= capacity) {
      ++(to == BusSide::host ? counters_.dropped_at_host : counters_.dropped_at_node);
      continue;
    }
    inbox.push_back(frame);
    ++(to == BusSide::host ? counters_.delivered_to_host : counters_.delivered_to_node);
  }
}

std::optional<hal::CanFrame> VirtualCanBus::take(BusSide to) {
  auto& inbox = rx_[index(to)];
  if (inbox.empty()) return std::nullopt;
  hal::CanFrame frame = inbox.front();
  inbox.pop_front();
  return frame;
}

}  // namespace tnv::can_host
