// HostAccess: command ownership and its timeout.
#include "firmware/can/host_access.hpp"

namespace tnv::fw::can {

ErrorCode HostAccess::ownership(CommandCode code) noexcept {
  const std::uint8_t from = host();
  if (from == kAnonymousHost) return ErrorCode::no_host;
  if (code == CommandCode::take_ownership) {
    if (owner_ != kAnonymousHost && owner_ != from) return ErrorCode::not_owner;
    owner_ = from;
    silent_ticks_ = 0;
    return ErrorCode::ok;
  }
  if (owner_ != from) return ErrorCode::not_owner;
  owner_ = kAnonymousHost;
  return ErrorCode::ok;
}

bool HostAccess::owner_timed_out(std::uint64_t ticks, std::uint32_t timeout_ms) noexcept {
  silent_ticks_ += ticks;
  if (timeout_ms == 0 || silent_ticks_ < timeout_ms) return false;
  owner_ = kAnonymousHost;
  return true;
}

}  // namespace tnv::fw::can
