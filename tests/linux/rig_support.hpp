#pragma once
// Shared by the rig tests: a scratch directory, a daemon config for the
// emulated board on a Unix socket, and the host's CAN client over the
// Unix-socket CAN link.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <memory>
#include <string>

#include "drivers/linux/unix_can_socket_api.hpp"
#include "firmware/can/param_table.hpp"
#include "tools/can/node_client.hpp"
#include "tools/can/socketcan_bus.hpp"
#include "tools/tnv-fw/fw_config.hpp"

namespace tnv::test {

class ScratchDir {
 public:
  ScratchDir() {
    std::string templ = (std::filesystem::temp_directory_path() / "tnv-linux-XXXXXX").string();
    path_ = ::mkdtemp(templ.data()) != nullptr ? templ : "";
    EXPECT_FALSE(path_.empty());
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const char* name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

inline fwd::DaemonConfig rig_config(const ScratchDir& dir) {
  fwd::DaemonConfig c;
  c.board.transport = "socket";
  c.board.path = dir.file("board.sock");
  c.board.reply_timeout_ms = 2000;  // generous: sanitizer builds on a busy machine
  c.can.interface_name = "unix:" + dir.file("can.sock");
  c.can.node_id = 1;
  c.rt.priority = 0;  // tests never take SCHED_FIFO (two cores shared with the build)
  c.rt.require = false;
  c.params.file = dir.file("params.bin");
  return c;
}

// The host end of the Unix-socket CAN link, and a protocol client on it.
struct HostLink {
  drivers::UnixCanSocketApi api;
  can_host::SocketCanBus bus;
  can_host::NodeClient client;
  explicit HostLink(const std::string& can_socket, std::uint8_t node = 1)
      : api(can_socket, drivers::UnixCanSocketApi::Role::host),
        bus(api, options(can_socket, node)),
        client(bus, node, client_options()) {}
  static can_host::SocketCanOptions options(const std::string& path, std::uint8_t node) {
    can_host::SocketCanOptions o;
    o.interface_name = "unix:" + path;
    o.node = node;
    return o;
  }
  static can_host::ClientOptions client_options() {
    can_host::ClientOptions o;
    o.timeout = can_host::Micros{3'000'000};
    return o;
  }
};

inline const fw::can::ParamDef& gamma_x() { return *fw::can::find_param("x.sliding.gamma"); }

}  // namespace tnv::test
