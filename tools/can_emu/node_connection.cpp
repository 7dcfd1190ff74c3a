#include "tools/can_emu/node_connection.hpp"

#include "drivers/linux/unix_can_socket_api.hpp"
#include "firmware/can/param_table.hpp"
#include "tools/can/socketcan_bus.hpp"
#include "tools/can/tracing_bus.hpp"

namespace tnv::can_host {

NodeConnection::~NodeConnection() = default;

std::unique_ptr<NodeConnection> NodeConnection::open(const ConnectionOptions& options,
                                                     std::vector<std::string>& notes) {
  std::unique_ptr<NodeConnection> c(new NodeConnection(options));
  const auto node = static_cast<std::uint8_t>(options.node);
  const std::string unix_path = drivers::unix_can_path(options.iface);  // "" unless unix:PATH
  if (options.emu) {
    EmulatedNodeOptions emu;
    emu.scenario = options.emu_scenario;
    emu.seed = options.emu_seed;
    emu.storage_path = options.emu_storage;
    emu.node = node;
    std::string error;
    std::unique_ptr<EmulatedBus> bus = EmulatedBus::create(emu, error);
    if (!bus) throw ConnectionInputError(error);
    if (!bus->startup_note().empty()) notes.push_back(bus->startup_note());
    // A saved set changes every later emulated result: say so.
    if (const std::size_t n = bus->saved_params_differing(); n > 0 && bus->startup_note().empty()) {
      std::string note = "note: the emulated node loaded the parameters saved in ";
      note.append(bus->storage_path()).append(" (").append(std::to_string(n)).append(n == 1 ? " differs" : " differ");
      note.append(" from a fresh node's; `params defaults` then `params save` resets them, --emu-storage FILE uses "
                  "another file)");
      notes.push_back(note);
    }
    if (bus->node_id() != node) {
      std::string message = "the emulated node has id ";
      message.append(std::to_string(bus->node_id())).append(" (can.node_id stored in ").append(bus->storage_path());
      message.append("); use --node ").append(std::to_string(bus->node_id()));
      throw std::runtime_error(message);
    }
    c->emulated_ = bus.get();
    c->bus_ = std::move(bus);
  } else {
    SocketCanOptions socket;
    socket.interface_name = options.iface;
    socket.node = node;
    // unix:PATH: the datagram link tnv-fw binds with `[can] interface =
    // "unix:PATH"` (docs/hil-rig.md), for rigs without vcan.
    if (!unix_path.empty()) {
      c->unix_link_ = std::make_unique<drivers::UnixCanSocketApi>(unix_path, drivers::UnixCanSocketApi::Role::host);
      c->bus_ = std::make_unique<SocketCanBus>(*c->unix_link_, socket);
    } else {
      c->bus_ = std::make_unique<SocketCanBus>(linux_socket_api(), socket);
    }
  }
  if (!options.trace.empty()) {
    const std::string iface = options.emu ? "emu" : unix_path.empty() ? options.iface : "unix";
    c->traced_ = std::make_unique<TracingBus>(*c->bus_, options.trace, iface);
  }
  ClientOptions client;
  client.timeout = Micros{static_cast<long long>(options.timeout_ms) * 1000};
  client.host_id = static_cast<std::uint8_t>(options.host_id);
  c->client_ = std::make_unique<NodeClient>(c->traced_ ? *c->traced_ : *c->bus_, node, client);
  // The first exchange: is there a node, and does it speak our protocol?
  const fw::can::ParamDef* version = fw::can::find_param("sys.protocol_version");
  const double theirs = c->client_->get(*version);
  if (theirs != static_cast<double>(fw::can::kProtocolVersion)) {
    std::string message = "node ";
    message.append(std::to_string(options.node)).append(" speaks protocol version ");
    message.append(std::to_string(static_cast<long long>(theirs))).append(", tnvctl version ");
    message.append(std::to_string(fw::can::kProtocolVersion));
    throw std::runtime_error(message);
  }
  return c;
}

std::string NodeConnection::release_ownership() noexcept {
  if (!client_ || !client_->holds_ownership()) return "";
  try {
    client_->release_ownership();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace tnv::can_host
