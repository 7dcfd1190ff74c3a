#pragma once
// HostBus over Linux SocketCAN (CAN_RAW): bound to one interface by name,
// a receive filter for the frames of one node (its id in the identifier's
// low 6 bits, standard frames only) plus CAN error frames, which are
// counted, never returned. Non-blocking socket; waits with poll().
#include <string>

#include "tools/can/host_bus.hpp"
#include "tools/can/socket_api.hpp"

namespace tnv::can_host {

struct SocketCanOptions {
  std::string interface_name = "can0";
  std::uint8_t node = 1;            // the node whose frames the filter lets through
  Micros send_timeout{100'000};     // how long a full transmit queue may block send()
};

class SocketCanBus final : public HostBus {
 public:
  // Opens, filters and binds; throws BusError naming the interface and
  // the failed step (e.g. "can0: no such network interface").
  SocketCanBus(SocketApi& api, const SocketCanOptions& options);
  ~SocketCanBus() override;
  SocketCanBus(const SocketCanBus&) = delete;
  SocketCanBus& operator=(const SocketCanBus&) = delete;

  void send(const hal::CanFrame& frame) override;
  std::optional<hal::CanFrame> receive(Micros timeout) override;
  Micros now() override { return api_.monotonic_now(); }
  std::string describe() const override { return options_.interface_name; }
  BusCounters counters() const override { return counters_; }

  // The last error frame's class bits (CAN_ERR_* of linux/can/error.h), 0 if none.
  canid_t last_error_class() const noexcept { return last_error_class_; }

 private:
  [[noreturn]] void fail(const char* step, int error) const;
  static const char* bind_failure(const std::string& interface_name, int error) noexcept;
  int wait_ms(Micros deadline);

  SocketApi& api_;
  SocketCanOptions options_;
  int fd_ = -1;
  BusCounters counters_{};
  canid_t last_error_class_ = 0;
};

// The receive filter for one node: standard, non-remote frames whose low
// 6 identifier bits are the node (every message of that node).
can_filter node_filter(std::uint8_t node) noexcept;

}  // namespace tnv::can_host
