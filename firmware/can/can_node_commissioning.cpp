// CanNode: commissioning mode. Safety parameters (Guard::commissioning in
// param_table) change only in it. It is entered by COMMAND
// enter_commissioning while the servo is disabled and no fault is latched,
// and left by leave_commissioning, by enable, by any accepted motion and by
// a fault. docs/safety.md "Commissioning".
#include "firmware/can/can_node.hpp"

namespace tnv::fw::can {

void CanNode::allow_commissioning(bool allowed) noexcept {
  commissioning_allowed_ = allowed;
  if (!allowed) commissioning_ = false;
}

bool CanNode::commissioning() const noexcept {
  return commissioning_ && task_.state() == MotionState::disabled && !task_.fault().active();
}

void CanNode::check_commissioning() noexcept { commissioning_ = commissioning(); }

ErrorCode CanNode::command_enter_commissioning() noexcept {
  if (!commissioning_allowed_) return ErrorCode::not_permitted;
  if (task_.fault().active()) return ErrorCode::faulted;
  if (task_.state() != MotionState::disabled) return ErrorCode::busy;
  commissioning_ = true;
  return ErrorCode::ok;
}

ErrorCode CanNode::commissioning_check(const ParamDef& p, std::uint32_t raw, std::uint32_t current) noexcept {
  check_commissioning();
  if (!safety_param(p) || commissioning_ || raw == current) return ErrorCode::ok;
  return ErrorCode::commissioning_required;
}

}  // namespace tnv::fw::can
