#pragma once
// One interface per axis loop (PID baseline, DVSC+DDC, R-DVSC+DDC).
// update() runs inside the 1 ms tick: no allocation, no exceptions.
#include <cstdint>

namespace tnv::fw {

// Measured state x_k = [position, velocity]^T (S1 eq. (3)).
struct AxisState {
  double position_mm = 0.0;
  double speed_mm_s = 0.0;
};

// Reference at this tick (x_ref,k) and the next one (x_ref,k+1).
struct AxisReference {
  double position_mm = 0.0;
  double speed_mm_s = 0.0;
  double next_position_mm = 0.0;
  double next_speed_mm_s = 0.0;
};

// Internal signals for telemetry and plots.
struct ControllerSignals {
  double s = 0.0;           // sliding variable s_k (0 for PID)
  double d_hat_mm_s = 0.0;  // disturbance estimate d^_k (integral term for PID)
  double u_mm_s = 0.0;      // last command, after clamping
  bool saturated = false;
};

enum class ControllerKind : std::uint8_t { pid = 0, dvsc = 1, rdvsc = 2 };

constexpr const char* to_string(ControllerKind kind) noexcept {
  switch (kind) {
    case ControllerKind::pid: return "pid";
    case ControllerKind::dvsc: return "dvsc";
    case ControllerKind::rdvsc: return "rdvsc";
  }
  return "?";
}

class AxisController {
 public:
  virtual ~AxisController() = default;
  // Speed command u_k in mm/s (clamped to the controller's u limit).
  virtual double update(const AxisState& x, const AxisReference& ref) noexcept = 0;
  // Forget all history (s_{k-1}, d^_{k-1}, integrators); called at servo-on.
  virtual void reset() noexcept = 0;
  virtual ControllerSignals signals() const noexcept = 0;
};

}  // namespace tnv::fw
