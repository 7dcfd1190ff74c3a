#pragma once
// One host's connection to one node, as tnvctl and the Python module open
// it: the in-process emulated node (--emu), a SocketCAN interface, or
// tnv-fw's Unix-socket CAN link ("unix:PATH"); optionally traced to a
// candump log; a NodeClient on it whose first request checks the node's
// protocol version.
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "tools/can/host_bus.hpp"
#include "tools/can/node_client.hpp"
#include "tools/can/socket_api.hpp"
#include "tools/can_emu/emulated_bus.hpp"

namespace tnv::can_host {

struct ConnectionOptions {
  std::string iface;  // SocketCAN interface, or unix:PATH (tnv-fw's Unix-socket CAN link)
  bool emu = false;   // the in-process emulated controller (iface unused)
  int node = 1;
  int host_id = 1;  // request tags, staged set and command ownership are this host's
  int timeout_ms = 250;
  std::string emu_scenario = "no-cut";
  int emu_seed = 0;
  std::string emu_storage;  // "" = default path
  std::string trace;        // "" = none; else every frame sent and received, candump -l format
};

// The emulated node could not be made (scenario or storage): bad input.
class ConnectionInputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

class NodeConnection {
 public:
  // Opens the bus and checks the node's protocol version. Throws
  // ConnectionInputError, BusError, RequestError, or std::runtime_error (a
  // node of another id or protocol version). `notes` gets what a person
  // should know about the emulated node's stored parameters.
  static std::unique_ptr<NodeConnection> open(const ConnectionOptions& options, std::vector<std::string>& notes);
  ~NodeConnection();
  NodeConnection(const NodeConnection&) = delete;
  NodeConnection& operator=(const NodeConnection&) = delete;

  NodeClient& client() noexcept { return *client_; }
  // The emulated controller, or nullptr on SocketCAN / unix:.
  EmulatedBus* emulated() const noexcept { return emulated_; }
  const ConnectionOptions& options() const noexcept { return options_; }
  // Gives back command ownership if this connection took it; "" or why it failed.
  std::string release_ownership() noexcept;

 private:
  explicit NodeConnection(ConnectionOptions options) : options_(std::move(options)) {}
  ConnectionOptions options_;
  std::unique_ptr<SocketApi> unix_link_;  // iface unix:PATH; outlives bus_, which uses it
  std::unique_ptr<HostBus> bus_;
  std::unique_ptr<HostBus> traced_;  // trace: records what passes through bus_
  EmulatedBus* emulated_ = nullptr;
  std::unique_ptr<NodeClient> client_;
};

}  // namespace tnv::can_host
