#pragma once
// The board's side of the register transport: answers framed requests
// (register_frame.hpp) against any hal::RegisterBus. tnv-board-emu serves
// the emulated board with it; tests serve a fake board in-process.
#include <cstdint>
#include <span>

#include "drivers/linux/register_frame.hpp"
#include "hal/register_bus.hpp"

namespace tnv::drivers {

// One request in, one reply out (its length returned). A request that does
// not decode is answered with bus_error (and the request's sequence number
// when it can be read), so the client fails fast instead of timing out.
std::size_t answer_register_request(std::span<const std::uint8_t> request, hal::RegisterBus& target,
                                    regwire::FrameBuffer& reply) noexcept;

struct ServeStats {
  std::uint64_t requests = 0;
  std::uint64_t bad_requests = 0;
};

enum class ServeEnd : std::uint8_t { peer_closed, stopped, link_error };

// Serves one connected SOCK_SEQPACKET socket until the peer closes, an
// error, or `stop_fd` (e.g. a signalfd or a pipe; -1 = none) is readable.
ServeEnd serve_register_connection(int fd, hal::RegisterBus& target, int stop_fd, ServeStats& stats) noexcept;

}  // namespace tnv::drivers
