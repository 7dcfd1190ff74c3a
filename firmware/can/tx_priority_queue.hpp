#pragma once
// Every frame the node sends waits here until the CAN port takes it, and
// leaves in CAN-id priority order (lowest identifier first, the order the
// wire arbitrates in; oldest first among equal identifiers). So a
// FAULT_EVENT, a reply or the heartbeat never waits behind telemetry or a
// capture upload, whatever the port's own queue does with what it holds.
//
// Fixed capacity, no allocation. When it is full, a droppable frame
// (telemetry) makes room: the lowest-priority droppable frame held goes
// if the new frame outranks it, else the new frame is the one dropped
// (push() says which; the node counts both). A frame that is not
// droppable is lost only when nothing droppable is left to evict.
#include <array>
#include <cstddef>
#include <cstdint>

#include "hal/can_port.hpp"

namespace tnv::fw::can {

class TxPriorityQueue {
 public:
  static constexpr std::size_t kCapacity = 48;

  enum class Push : std::uint8_t {
    queued,           // kept, nothing lost
    evicted_other,    // kept, a lower-priority droppable frame was dropped for it
    dropped,          // not kept
  };

  Push push(const hal::CanFrame& frame, bool droppable) noexcept {
    if (size_ < kCapacity) {
      slots_[size_++] = {frame, next_order_++, droppable};
      return Push::queued;
    }
    std::size_t victim = kCapacity;
    for (std::size_t i = 0; i < size_; ++i) {
      if (!slots_[i].droppable) continue;
      if (victim == kCapacity || after(slots_[i], slots_[victim])) victim = i;
    }
    if (victim == kCapacity) return Push::dropped;
    const Slot incoming{frame, next_order_, droppable};
    if (droppable && !after(slots_[victim], incoming)) return Push::dropped;  // the newcomer ranks lowest
    ++next_order_;
    slots_[victim] = incoming;
    return Push::evicted_other;
  }

  // The frame to send next: the lowest identifier, oldest among equals.
  const hal::CanFrame& top() const noexcept { return slots_[top_index()].frame; }
  void pop() noexcept {
    const std::size_t i = top_index();
    slots_[i] = slots_[size_ - 1];
    --size_;
  }
  bool empty() const noexcept { return size_ == 0; }
  std::size_t size() const noexcept { return size_; }
  void clear() noexcept { size_ = 0; }

 private:
  struct Slot {
    hal::CanFrame frame{};
    std::uint32_t order = 0;  // push order (wraps after 4e9 frames: harmless, only ties use it)
    bool droppable = false;
  };
  static std::uint32_t key(const hal::CanFrame& f) noexcept {
    return f.extended ? (f.id & 0x1FFFFFFFu) | 0x20000000u : f.id;  // never sent by the node, ranked last
  }
  // a goes out after b.
  static bool after(const Slot& a, const Slot& b) noexcept {
    const std::uint32_t ka = key(a.frame);
    const std::uint32_t kb = key(b.frame);
    if (ka != kb) return ka > kb;
    return static_cast<std::int32_t>(a.order - b.order) > 0;
  }
  std::size_t top_index() const noexcept {
    std::size_t best = 0;
    for (std::size_t i = 1; i < size_; ++i)
      if (after(slots_[best], slots_[i])) best = i;
    return best;
  }

  std::array<Slot, kCapacity> slots_{};
  std::size_t size_ = 0;
  std::uint32_t next_order_ = 0;
};

}  // namespace tnv::fw::can
