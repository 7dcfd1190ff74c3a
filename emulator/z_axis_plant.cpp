#include "emulator/z_axis_plant.hpp"

namespace tnv::emu {

ZAxisPlant::ZAxisPlant(const ZAxisParams& params) noexcept : params_(params), axis_(params.plant) {}

void ZAxisPlant::step(double command_mm_s, double disturbance_mm_s) noexcept {
  axis_.step(command_mm_s, params_.gravity_mm_s + disturbance_mm_s);
  stop_at_end_stops();
}

void ZAxisPlant::step_for(double command_mm_s, double disturbance_mm_s, double duration_s) noexcept {
  axis_.step_for(command_mm_s, params_.gravity_mm_s + disturbance_mm_s, duration_s);
  stop_at_end_stops();
}

// A rigid stop: the head stays at it with speed 0 (and then, friction on,
// the Karnopp test decides whether the drive pulls it away again).
void ZAxisPlant::stop_at_end_stops() noexcept {
  const double top_stop_mm = params_.travel_top_mm + params_.overtravel_mm;
  const double bottom_stop_mm = params_.travel_bottom_mm - params_.overtravel_mm;
  const double p = axis_.position_mm();
  if (p > top_stop_mm || p < bottom_stop_mm) {
    if (!at_stop_) ++end_stop_hits_;  // one hit per arrival, not per sub-step pressed against it
    at_stop_ = true;
    axis_.set_state(p > top_stop_mm ? top_stop_mm : bottom_stop_mm, 0.0, true);
  } else if (p < top_stop_mm && p > bottom_stop_mm) {
    at_stop_ = false;
  }
}

}  // namespace tnv::emu
