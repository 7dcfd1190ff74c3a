// CommissioningMode: entered only while disabled and fault-free, left as
// soon as that no longer holds.
#include "firmware/can/commissioning_mode.hpp"

namespace tnv::fw::can {

void CommissioningMode::allow(bool allowed) noexcept {
  allowed_ = allowed;
  if (!allowed) entered_ = false;
}

bool CommissioningMode::active() const noexcept {
  return entered_ && task_.state() == MotionState::disabled && !task_.fault().active();
}

bool CommissioningMode::refresh() noexcept {
  entered_ = active();
  return entered_;
}

ErrorCode CommissioningMode::enter() noexcept {
  if (!allowed_) return ErrorCode::not_permitted;
  if (task_.fault().active()) return ErrorCode::faulted;
  if (task_.state() != MotionState::disabled) return ErrorCode::busy;
  entered_ = true;
  return ErrorCode::ok;
}

ErrorCode CommissioningMode::check_change(const ParamDef& p, std::uint32_t raw, std::uint32_t current) noexcept {
  const bool on = refresh();
  if (!safety_param(p) || on || raw == current) return ErrorCode::ok;
  return ErrorCode::commissioning_required;
}

}  // namespace tnv::fw::can
