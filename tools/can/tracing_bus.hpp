#pragma once
// A HostBus that records every frame it sends and receives, in candump's
// log format (candump_log.hpp), to a file, one line at a time and flushed,
// so a session that ends badly still leaves its trace. The time stamp is
// the transport's own clock (simulated on the emulated node).
#include <cstdio>
#include <memory>
#include <string>

#include "tools/can/host_bus.hpp"

namespace tnv::can_host {

class TracingBus final : public HostBus {
 public:
  // Throws BusError when `path` cannot be opened for writing.
  TracingBus(HostBus& inner, const std::string& path, std::string iface_name);
  ~TracingBus() override;
  TracingBus(const TracingBus&) = delete;
  TracingBus& operator=(const TracingBus&) = delete;

  void send(const hal::CanFrame& frame) override;
  std::optional<hal::CanFrame> receive(Micros timeout) override;
  Micros now() override { return inner_.now(); }
  std::string describe() const override { return inner_.describe(); }
  BusCounters counters() const override { return inner_.counters(); }

 private:
  void record(const hal::CanFrame& frame);
  HostBus& inner_;
  std::FILE* file_ = nullptr;
  std::string iface_;
};

}  // namespace tnv::can_host
