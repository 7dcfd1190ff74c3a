#include "tools/tnvctl/session.hpp"

#include <cstdio>
#include <iostream>

#include "drivers/linux/unix_can_socket_api.hpp"
#include "firmware/can/param_table.hpp"
#include "tools/can/socketcan_bus.hpp"
#include "tools/can/tracing_bus.hpp"

namespace tnv::tnvctl {

void Report::line(const std::string& text) const {
  if (json_) return;
  std::ostream& out = summary_on_stderr_ ? std::cerr : std::cout;  // stdout kept for the CSV rows
  out << text << '\n';
  out.flush();
}

void Session::open() {
  const auto node = static_cast<std::uint8_t>(options_.node);
  const std::string unix_path = drivers::unix_can_path(options_.iface);  // "" unless --iface unix:PATH
  if (options_.emu) {
    can_host::EmulatedNodeOptions emu;
    emu.scenario = options_.emu_scenario;
    emu.seed = options_.emu_seed;
    emu.storage_path = options_.emu_storage;
    emu.node = node;
    std::string error;
    std::unique_ptr<can_host::EmulatedBus> bus = can_host::EmulatedBus::create(emu, error);
    if (!bus) throw BadInput(error);
    if (!bus->startup_note().empty()) std::fprintf(stderr, "tnvctl: %s\n", bus->startup_note().c_str());
    // A saved set changes every later --emu result: say so.
    if (const std::size_t n = bus->saved_params_differing(); n > 0 && bus->startup_note().empty())
      std::fprintf(stderr,
                   "tnvctl: note: the emulated node loaded the parameters saved in %s (%zu %s from a fresh node's; "
                   "`params defaults` then `params save` resets them, --emu-storage FILE uses another file)\n",
                   bus->storage_path().c_str(), n, n == 1 ? "differs" : "differ");
    if (bus->node_id() != node) {
      std::string message = "the emulated node has id ";
      message.append(std::to_string(bus->node_id())).append(" (can.node_id stored in ").append(bus->storage_path());
      message.append("); use --node ").append(std::to_string(bus->node_id()));
      throw RunFailed(message);
    }
    emulated_ = bus.get();
    bus_ = std::move(bus);
  } else {
    can_host::SocketCanOptions socket;
    socket.interface_name = options_.iface;
    socket.node = node;
    // unix:PATH: the datagram link tnv-fw binds with `[can] interface =
    // "unix:PATH"` (docs/hil-rig.md), for rigs without vcan.
    if (!unix_path.empty()) {
      unix_link_ = std::make_unique<drivers::UnixCanSocketApi>(unix_path, drivers::UnixCanSocketApi::Role::host);
      bus_ = std::make_unique<can_host::SocketCanBus>(*unix_link_, socket);
    } else {
      bus_ = std::make_unique<can_host::SocketCanBus>(can_host::linux_socket_api(), socket);
    }
  }
  if (!options_.trace.empty()) {
    const std::string iface = options_.emu ? "emu" : unix_path.empty() ? options_.iface : "unix";
    traced_ = std::make_unique<can_host::TracingBus>(*bus_, options_.trace, iface);
  }
  can_host::ClientOptions client;
  client.timeout = can_host::Micros{static_cast<long long>(options_.timeout_ms) * 1000};
  client.host_id = static_cast<std::uint8_t>(options_.host_id);
  client_ = std::make_unique<can_host::NodeClient>(traced_ ? *traced_ : *bus_, node, client);
  // The first exchange: is there a node, and does it speak our protocol?
  const fw::can::ParamDef* version = fw::can::find_param("sys.protocol_version");
  const double theirs = client_->get(*version);
  if (theirs != static_cast<double>(fw::can::kProtocolVersion)) {
    std::string message = "node ";
    message.append(std::to_string(options_.node)).append(" speaks protocol version ");
    message.append(std::to_string(static_cast<long long>(theirs))).append(", tnvctl version ");
    message.append(std::to_string(fw::can::kProtocolVersion));
    throw RunFailed(message);
  }
}

can_host::NodeClient& Session::client() {
  if (!client_) open();
  return *client_;
}

void Session::end() noexcept {
  if (!client_ || !client_->holds_ownership()) return;
  try {
    client_->release_ownership();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tnvctl: could not release command ownership: %s\n", e.what());
  }
}

can_host::EmulatedBus* Session::emulated() {
  client();
  return emulated_;
}

}  // namespace tnv::tnvctl
