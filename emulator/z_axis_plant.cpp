#include "emulator/z_axis_plant.hpp"

namespace tnv::emu {

AxisLoad z_axis_load(const ZAxisParams& params) noexcept {
  return AxisLoad{.constant_mm_s = params.gravity_mm_s,
                  .stop_low_mm = params.travel_bottom_mm - params.overtravel_mm,
                  .stop_high_mm = params.travel_top_mm + params.overtravel_mm};
}

bool EndStops::apply(AxisState& s) noexcept {
  const double p = s.position_mm;
  if (p > high_mm_ || p < low_mm_) {
    if (!at_stop_) ++hits_;
    at_stop_ = true;
    s = AxisState{.position_mm = p > high_mm_ ? high_mm_ : low_mm_, .speed_mm_s = 0.0, .stuck = true};
    return true;
  }
  if (p < high_mm_ && p > low_mm_) at_stop_ = false;
  return false;
}

ZAxisPlant::ZAxisPlant(const ZAxisParams& params, const AxisPlantParams& law) noexcept
    : params_(params), load_(z_axis_load(params)), axis_(law), stops_(load_) {}

void ZAxisPlant::step(double command_mm_s, double disturbance_mm_s) noexcept {
  axis_.step(command_mm_s, load_.constant_mm_s + disturbance_mm_s);
  stop_at_end_stops();
}

void ZAxisPlant::step_for(double command_mm_s, double disturbance_mm_s, double duration_s) noexcept {
  axis_.step_for(command_mm_s, load_.constant_mm_s + disturbance_mm_s, duration_s);
  stop_at_end_stops();
}

void ZAxisPlant::stop_at_end_stops() noexcept {
  AxisState s = axis_.state();
  if (stops_.apply(s)) axis_.set_state(s);
}

}  // namespace tnv::emu
