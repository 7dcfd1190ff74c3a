#pragma once
// Unix-domain SOCK_SEQPACKET sockets: the register transport between the
// firmware process and the board-emulator process (message boundaries
// kept, connection-oriented, so a dead peer is seen at once).
#include <string>

namespace tnv::drivers {

// Binds and listens at `path` (a stale socket file is replaced); -1 with a
// one-line `error`.
int listen_seqpacket(const std::string& path, std::string& error);
// Connects to `path`, retrying every 20 ms for up to `timeout_ms` (the
// server may still be starting); -1 with a one-line `error`.
int connect_seqpacket(const std::string& path, int timeout_ms, std::string& error);
// accept() on a listening socket; -1 on error (errno kept).
int accept_seqpacket(int listen_fd);

}  // namespace tnv::drivers
