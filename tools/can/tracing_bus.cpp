#include "tools/can/tracing_bus.hpp"

#include <cerrno>
#include <cstring>

#include "tools/can/candump_log.hpp"

namespace tnv::can_host {

TracingBus::TracingBus(HostBus& inner, const std::string& path, std::string iface_name)
    : inner_(inner), iface_(std::move(iface_name)) {
  file_ = std::fopen(path.c_str(), "w");
  if (file_ == nullptr) throw BusError("cannot write the trace " + path + ": " + std::strerror(errno));
}

TracingBus::~TracingBus() {
  if (file_ != nullptr) std::fclose(file_);
}

void TracingBus::record(const hal::CanFrame& frame) {
  const double t_s = static_cast<double>(inner_.now().count()) * 1e-6;
  const std::string line = candump_line(t_s, iface_, frame);
  std::fputs(line.c_str(), file_);
  std::fputc('\n', file_);
  std::fflush(file_);
}

void TracingBus::send(const hal::CanFrame& frame) {
  inner_.send(frame);
  record(frame);
}

std::optional<hal::CanFrame> TracingBus::receive(Micros timeout) {
  std::optional<hal::CanFrame> frame = inner_.receive(timeout);
  if (frame) record(*frame);
  return frame;
}

}  // namespace tnv::can_host
