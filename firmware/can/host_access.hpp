#pragma once
// Who may do what on the CAN node: the request being handled (its tag,
// request_tag.hpp, and whether it came on the broadcast node 0) and command
// ownership. Commands that move or change the machine need ownership,
// taken and released explicitly (COMMAND take_ownership / release_ownership)
// and lost when its host is silent for can.host_timeout_ms; reads are open
// to every host (docs/can-protocol.md "Bus priority, tags, hosts and ownership").
//
// Bounded work, no allocation, exceptions, locks or logging: it runs in
// CanNode::service().
#include <cstdint>

#include "firmware/can/protocol_enums.hpp"
#include "firmware/can/request_tag.hpp"

namespace tnv::fw::can {

class HostAccess {
 public:
  // A request arrives: its tag (byte 0, echoed by its reply) and whether it came on node 0.
  void begin_request(std::uint8_t tag, bool broadcast) noexcept {
    tag_ = tag;
    broadcast_ = broadcast;
  }
  // An answer to a request kept for later (a save, load or a SEGMENT waiting
  // for its tail) echoes that request's tag.
  void answer_as(std::uint8_t tag) noexcept { tag_ = tag; }

  std::uint8_t tag() const noexcept { return tag_; }
  std::uint8_t host() const noexcept { return host_of_tag(tag_); }
  bool broadcast() const noexcept { return broadcast_; }
  std::uint8_t owner() const noexcept { return owner_; }  // host id holding command ownership, 0 none
  // The current request's host holds command ownership.
  bool owns() const noexcept { return host() != kAnonymousHost && host() == owner_; }

  // A valid frame from `host`: the owner's silence ends.
  void heard_from(std::uint8_t host) noexcept {
    if (host != kAnonymousHost && host == owner_) silent_ticks_ = 0;
  }
  // COMMAND take_ownership / release_ownership for the current request's
  // host. take: granted when nobody holds ownership or the host already
  // does (taking it again is harmless); release: only by the owner.
  ErrorCode ownership(CommandCode code) noexcept;
  // `ticks` passed: true (and ownership lost) when the owner has been silent
  // for `timeout_ms` ticks or more (0: never). True again each call after that.
  bool owner_timed_out(std::uint64_t ticks, std::uint32_t timeout_ms) noexcept;

 private:
  std::uint8_t tag_ = 0;           // tag of the request being handled (echoed by its reply)
  bool broadcast_ = false;         // the request being handled came on node 0
  std::uint8_t owner_ = kAnonymousHost;
  std::uint64_t silent_ticks_ = 0;  // ticks since the last valid frame from the owner
};

}  // namespace tnv::fw::can
