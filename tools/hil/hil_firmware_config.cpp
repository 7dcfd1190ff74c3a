#include "tools/hil/hil_firmware_config.hpp"

#include <cmath>

#include "emulator/quadrature_encoder.hpp"

namespace tnv::hil {

fw::FirmwareConfig firmware_config_for(const emu::Scenario& scenario, const fw::FirmwareConfig& base) {
  fw::FirmwareConfig cfg = base;
  const double speed_at_full_scale_mm_s = scenario.dac.rpm_at_full_scale * scenario.encoder.lead_mm / 60.0;
  for (auto& axis : cfg.axis) {
    axis.count_mm = scenario.encoder.count_mm();
    axis.dac.bits = static_cast<unsigned>(scenario.dac.bits);
    axis.dac.full_scale_mm_s = speed_at_full_scale_mm_s;
  }
  // The emulated machine powers up at rest where emu::power_up_position_mm puts each axis.
  for (const hal::Axis a : hal::kAxes)
    cfg.axis[hal::index(a)].home_position_mm = homed_position_mm(scenario, a, emu::power_up_position_mm(scenario, a));
  return cfg;
}

double homed_position_mm(const emu::Scenario& scenario, hal::Axis axis, double position_mm) {
  const double q_mm = scenario.encoder.count_mm();
  const double offset_counts = scenario.encoder.offset_counts(axis);
  const emu::QuadratureEncoder encoder(q_mm, offset_counts);
  return static_cast<double>(encoder.count(position_mm)) * q_mm - offset_counts * q_mm;
}

fw::CircleSpec circle_spec_for(const emu::Scenario& scenario) noexcept {
  return {scenario.circle.radius_mm, scenario.circle.feed_mm_s, scenario.circle.ramp_s, scenario.circle.dwell_s};
}

}  // namespace tnv::hil
