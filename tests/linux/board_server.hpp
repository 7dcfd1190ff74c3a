#pragma once
// The emulated board for the daemon's in-process rig tests: a machine that
// advances one tick per snapshot read (TickingBus), served on a Unix
// seqpacket socket from a thread. Declare it before the daemon: the daemon
// goes first, closing the register link, and join() then sees the peer leave.
#include <sys/socket.h>
#include <unistd.h>

#include <string>
#include <thread>

#include "drivers/linux/register_server.hpp"
#include "drivers/linux/unix_seqpacket.hpp"
#include "emulator/machine.hpp"
#include "emulator/scenario_file.hpp"
#include "tools/tnv-board-emu/ticking_bus.hpp"

namespace tnv::test {

class BoardServer {
 public:
  explicit BoardServer(const std::string& socket_path, const std::string& scenario = "no-cut")
      : machine_(*emu::resolve_scenario(scenario).scenario), ticking_(machine_) {
    listen_fd_ = drivers::listen_seqpacket(socket_path, error_);
    if (listen_fd_ < 0) return;
    server_ = std::thread([this] {
      const int fd = drivers::accept_seqpacket(listen_fd_);
      if (fd < 0) return;  // shut down before a daemon connected
      drivers::ServeStats stats;
      end_ = drivers::serve_register_connection(fd, ticking_, -1, stats);
      ::close(fd);
    });
  }
  BoardServer(const BoardServer&) = delete;
  BoardServer& operator=(const BoardServer&) = delete;
  ~BoardServer() { join(); }

  bool listening() const noexcept { return listen_fd_ >= 0; }
  const std::string& error() const noexcept { return error_; }

  // Waits for the connection to end (a daemon that never connected: the
  // listening socket is shut down) and says how it ended.
  drivers::ServeEnd join() {
    if (listen_fd_ >= 0) ::shutdown(listen_fd_, SHUT_RDWR);
    if (server_.joinable()) server_.join();
    if (listen_fd_ >= 0) ::close(listen_fd_);
    listen_fd_ = -1;
    return end_;
  }

  emu::Machine& machine() noexcept { return machine_; }
  const board_emu::TickingBus& ticking() const noexcept { return ticking_; }

 private:
  emu::Machine machine_;
  board_emu::TickingBus ticking_;
  std::string error_;
  int listen_fd_ = -1;
  drivers::ServeEnd end_ = drivers::ServeEnd::link_error;
  std::thread server_;
};

}  // namespace tnv::test
