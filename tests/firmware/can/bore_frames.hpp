#pragma once
// BORE_GAUGE frames from the test host and a bench with the planner on, for
// the node's boring tests (can_node_boring*_test.cpp, the fuzz seeds).
#include <array>
#include <cmath>

#include "firmware/adaptive/boring/boring_station.hpp"
#include "tests/firmware/can/node_bench.hpp"

namespace tnv::test {

// record (part, two readings in mm, on the wire's 0.1 um grid), query or restart.
inline hal::CanFrame bore_gauge(std::uint8_t node, fw::can::BoreOp op, std::uint32_t part = 0, double top_mm = 0.0,
                                double bottom_mm = 0.0) {
  using fw::can::MessageId;
  hal::CanFrame f = frame_to(MessageId::bore_gauge, node);
  set_raw(f, MessageId::bore_gauge, "op", static_cast<std::uint32_t>(op));
  set_raw(f, MessageId::bore_gauge, "part", part);
  set_value(f, MessageId::bore_gauge, "top", top_mm);
  set_value(f, MessageId::bore_gauge, "bottom", bottom_mm);
  return f;
}

// The readings as the node decodes them from a BORE_GAUGE frame.
inline std::array<double, 2> bore_readings(const hal::CanFrame& f) {
  using fw::can::MessageId;
  return {value_of(f, MessageId::bore_gauge, "top"), value_of(f, MessageId::bore_gauge, "bottom")};
}

// Telemetry off, planner on, S4's defaults.
inline fw::can::NodeSettings boring_settings() {
  fw::can::NodeSettings s = quiet_settings();
  s.bore.enabled = true;
  return s;
}

// S4's process (section 5): parts 1-10, 11-20 and from 21 on, d = C S^alpha L^beta,
// plus a deterministic gauge error of up to `error_mm`.
inline double s4_deflection_mm(int part, double infeed_mm_rev, double overhang_mm, double error_mm = 0.0) {
  const double c = part < 11 ? 0.0871 : part < 21 ? 0.15 : 0.075;
  const double a = part < 11 ? 0.5025 : part < 21 ? 0.7 : 0.6;
  const double b = part < 11 ? 0.2676 : part < 21 ? 0.4 : 0.5;
  return c * std::pow(infeed_mm_rev, a) * std::pow(overhang_mm, b) + error_mm * std::sin(2.3 * part + overhang_mm);
}

// The bore error the gauge reads for that deflection (S4 eq. (11) inverted, phi = 60 deg, d0 = 0.1165 mm).
inline double s4_bore_error_mm(double deflection_mm) {
  return fw::bore_error_from_deflection_mm(deflection_mm, 0.1165, 60.0);
}

}  // namespace tnv::test
