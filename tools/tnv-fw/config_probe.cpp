#include "tools/tnv-fw/config_probe.hpp"

#include "drivers/linux/gpio_lines.hpp"
#include "drivers/linux/socket_api.hpp"
#include "drivers/linux/socketcan_port.hpp"
#include "drivers/linux/spidev_register_bus.hpp"
#include "drivers/linux/unix_can_socket_api.hpp"

namespace tnv::fwd {

bool ProbeReport::ok() const noexcept { return failures() == 0; }

std::size_t ProbeReport::failures() const noexcept {
  std::size_t n = 0;
  for (const ProbeItem& item : items) n += item.ok ? 0 : 1;
  return n;
}

namespace {

// The drivers' messages start with the device (or the line's key and
// spec); the report names those already.
std::string without_prefix(const std::string& error, const std::string& prefix) {
  return error.rfind(prefix, 0) == 0 ? error.substr(prefix.size()) : error;
}

ProbeItem board_item(const BoardConfig& board) {
  ProbeItem item{"board.path " + board.path, true, true, ""};
  if (board.transport == "socket") {
    item.probed = false;
    item.detail = "socket transport (the board emulator's server), not a device";
    return item;
  }
  std::string error;
  if (drivers::SpidevRegisterBus::open({board.path, board.spi_speed_hz}, error) == nullptr) {
    item.ok = false;
    item.detail = without_prefix(error, board.path + ": ");
  }
  return item;
}

// One line alone, so that every configured line gets its own answer.
ProbeItem line_item(const std::string& key, const drivers::LineSpec& spec, drivers::LineConfig one) {
  ProbeItem item{"lines." + key + " " + spec.describe(), true, true, ""};
  std::string error;
  if (drivers::open_board_lines(one, error) == nullptr) {
    item.ok = false;
    item.detail = without_prefix(error, "lines." + key + " (" + spec.describe() + "): ");
  }
  return item;
}

ProbeItem can_item(const CanConfig& can) {
  ProbeItem item{"can.interface " + can.interface_name, true, true, ""};
  if (!drivers::unix_can_path(can.interface_name).empty()) {
    item.probed = false;
    item.detail = "a unix: path, created by the daemon at its start";
    return item;
  }
  drivers::SocketCanPortOptions options;
  options.interface_name = can.interface_name;
  options.node_id = can.node_id;
  std::string error;
  if (drivers::SocketCanPort::open(drivers::linux_socket_api(), options, error) == nullptr) {
    item.ok = false;
    item.detail = without_prefix(error, can.interface_name + ": ");
  }
  return item;
}

}  // namespace

ProbeReport probe_devices(const DaemonConfig& config) {
  ProbeReport report;
  report.items.push_back(board_item(config.board));
  if (config.lines.tick.configured()) {
    drivers::LineConfig one;
    one.tick = config.lines.tick;
    report.items.push_back(line_item("tick", config.lines.tick, one));
  }
  for (std::size_t i = 0; i < drivers::kInputLineCount; ++i) {
    const drivers::LineSpec& spec = config.lines.inputs[i];
    if (!spec.configured()) continue;
    drivers::LineConfig one;
    one.inputs[i] = spec;
    report.items.push_back(line_item(drivers::line_key(static_cast<drivers::InputLine>(i)), spec, one));
  }
  for (std::size_t i = 0; i < drivers::kOutputLineCount; ++i) {
    const drivers::LineSpec& spec = config.lines.outputs[i];
    if (!spec.configured()) continue;
    drivers::LineConfig one;
    one.outputs[i] = spec;
    report.items.push_back(line_item(drivers::line_key(static_cast<drivers::OutputLine>(i)), spec, one));
  }
  report.items.push_back(can_item(config.can));
  return report;
}

}  // namespace tnv::fwd
