#pragma once
// A HostBus with a scripted node behind it, in fake time: every frame the
// host sends goes to `on_request`, which queues replies (each delivered
// `latency` later); receive() advances the clock to the next reply or by
// the whole timeout.
#include <deque>
#include <functional>
#include <vector>

#include "firmware/can/frame_codec.hpp"
#include "tools/can/host_bus.hpp"

namespace tnv::test {

class ScriptedNodeBus final : public can_host::HostBus {
 public:
  std::function<void(const hal::CanFrame&, ScriptedNodeBus&)> on_request;
  can_host::Micros latency{300};
  std::vector<hal::CanFrame> sent;

  void reply(const hal::CanFrame& f) { pending_.push_back({now_ + latency + can_host::Micros{static_cast<long long>(pending_.size())}, f}); }

  void send(const hal::CanFrame& frame) override {
    sent.push_back(frame);
    if (on_request) on_request(frame, *this);
  }
  std::optional<hal::CanFrame> receive(can_host::Micros timeout) override {
    if (!pending_.empty() && pending_.front().at <= now_ + timeout) {
      now_ = std::max(now_, pending_.front().at);
      const hal::CanFrame f = pending_.front().frame;
      pending_.pop_front();
      return f;
    }
    now_ += timeout;
    return std::nullopt;
  }
  can_host::Micros now() override { return now_; }
  std::string describe() const override { return "scripted bus"; }
  can_host::BusCounters counters() const override { return {}; }

 private:
  struct Timed {
    can_host::Micros at;
    hal::CanFrame frame;
  };
  std::deque<Timed> pending_;
  can_host::Micros now_{0};
};

}  // namespace tnv::test
