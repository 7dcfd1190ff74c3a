#pragma once
// Replies the CAN port could not take at once, kept in order for the next
// service(). Fixed capacity: when it is full the newest reply is dropped
// (and counted by the node).
#include <array>
#include <cstddef>

#include "hal/can_port.hpp"

namespace tnv::fw::can {

class TxQueue {
 public:
  static constexpr std::size_t kCapacity = 32;

  bool push(const hal::CanFrame& frame) noexcept {
    if (size_ == kCapacity) return false;
    frames_[(head_ + size_) % kCapacity] = frame;
    ++size_;
    return true;
  }
  const hal::CanFrame& front() const noexcept { return frames_[head_]; }
  void pop() noexcept {
    head_ = (head_ + 1) % kCapacity;
    --size_;
  }
  bool empty() const noexcept { return size_ == 0; }
  std::size_t size() const noexcept { return size_; }

 private:
  std::array<hal::CanFrame, kCapacity> frames_{};
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

}  // namespace tnv::fw::can
