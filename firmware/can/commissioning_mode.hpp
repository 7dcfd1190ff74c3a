#pragma once
// Commissioning mode of the CAN node (docs/safety.md "Commissioning"):
// safety parameters (Guard::commissioning in param_table) change only in
// it. It is entered by COMMAND enter_commissioning while the servo is
// disabled and no fault is latched, if the integration allows it (tnv-fw:
// [safety] allow_commissioning), and left by leave_commissioning, by
// enable, by any motion asked for and by a fault.
//
// Bounded work, no allocation, exceptions, locks or logging: it runs in
// CanNode::service().
#include <cstdint>

#include "firmware/can/param_table.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "firmware/tick/tick_task.hpp"

namespace tnv::fw::can {

class CommissioningMode {
 public:
  explicit CommissioningMode(const TickTask& task) noexcept : task_(task) {}

  // The local permission; without it enter() answers not_permitted.
  void allow(bool allowed) noexcept;
  // In the mode now: entered, and the machine still allows it.
  bool active() const noexcept;
  // Leaves the mode when the machine no longer allows it (not disabled, or
  // a fault latched); returns active(). Each service() and before a change.
  bool refresh() noexcept;
  ErrorCode enter() noexcept;  // COMMAND enter_commissioning
  void leave() noexcept { entered_ = false; }
  // A set / stage writing `raw` into `p` (now `current`): commissioning_required
  // for a safety parameter that would change outside the mode, else ok.
  ErrorCode check_change(const ParamDef& p, std::uint32_t raw, std::uint32_t current) noexcept;

 private:
  const TickTask& task_;
  bool entered_ = false;   // safety parameters writable (entered while disabled)
  bool allowed_ = true;    // the local permission to enter it
};

}  // namespace tnv::fw::can
