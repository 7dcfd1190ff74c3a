#pragma once
// The vertical axis (reference plant "Z axis"): the table axis' law with the
// head's uncompensated weight as one more constant disturbance,
//   tau_Z dv/dt = K u + d_g + d_cut,z - f_fric(v) - v,
// so the Karnopp stick test the axis plant applies to K u + d becomes
// |K u + d_g + d_cut,z| <= f_s: an idle head (u = 0) stays put, a servo-off
// head sags only when something pushes it past f_s. Mechanical end stops
// overtravel_mm beyond the travel's ends stop the head dead (a crash into
// the stop, counted). The home switch at the top is actuated at and above
// home_switch_mm. Position is the spindle nose, machine coordinates.
#include <cstdint>

#include "emulator/axis_plant.hpp"
#include "emulator/scenario.hpp"

namespace tnv::emu {

class ZAxisPlant {
 public:
  explicit ZAxisPlant(const ZAxisParams& params) noexcept;

  // One 10 us sub-step; disturbance_mm_s is d_cut,z (the process' axial load).
  void step(double command_mm_s, double disturbance_mm_s = 0.0) noexcept;
  // The same law over any duration (tests).
  void step_for(double command_mm_s, double disturbance_mm_s, double duration_s) noexcept;

  double position_mm() const noexcept { return axis_.position_mm(); }
  double speed_mm_s() const noexcept { return axis_.speed_mm_s(); }
  bool stuck() const noexcept { return axis_.stuck(); }
  bool home_switch() const noexcept { return axis_.position_mm() >= params_.home_switch_mm; }
  // The head is outside its travel (between a travel end and its stop).
  bool beyond_travel() const noexcept {
    return axis_.position_mm() > params_.travel_top_mm || axis_.position_mm() < params_.travel_bottom_mm;
  }
  std::uint64_t end_stop_hits() const noexcept { return end_stop_hits_; }
  const AxisPlant& axis() const noexcept { return axis_; }
  const ZAxisParams& params() const noexcept { return params_; }

  void set_state(double position_mm, double speed_mm_s, bool stuck = false) noexcept {
    axis_.set_state(position_mm, speed_mm_s, stuck);
  }

 private:
  void stop_at_end_stops() noexcept;

  ZAxisParams params_;
  AxisPlant axis_;
  std::uint64_t end_stop_hits_ = 0;
  bool at_stop_ = false;
};

}  // namespace tnv::emu
