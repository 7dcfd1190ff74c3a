#pragma once
// The vertical axis (reference plant "Z axis"): the table axis' law with the
// head's uncompensated weight as one more constant disturbance,
//   tau_Z dv/dt = K u + d_g + d_cut,z - f_fric(v) - v,
// so the Karnopp stick test the axis plant applies to K u + d becomes
// |K u + d_g + d_cut,z| <= f_s: an idle head (u = 0) stays put, a servo-off
// head sags only when something pushes it past f_s. Mechanical end stops
// overtravel_mm beyond the travel's ends stop the head dead (a crash into
// the stop, counted). Position is the spindle nose, machine coordinates.
// The home switch is the board's ([board] home_z_mm: emu::Machine).
//
// emu::Machine steps every axis of the list with the same two pieces:
// AxisLoad (the constant load and the stops of an axis; none on X and Y)
// and EndStops (the stop itself and its count), so Z's law is written once.
#include <cstddef>
#include <cstdint>
#include <limits>

#include "emulator/axis_plant.hpp"
#include "emulator/scenario.hpp"

namespace tnv::emu {

// What an axis carries beyond the table's law: a constant disturbance (the
// head's weight) and hard stops (+-inf: none).
struct AxisLoad {
  double constant_mm_s = 0.0;
  double stop_low_mm = -std::numeric_limits<double>::infinity();
  double stop_high_mm = std::numeric_limits<double>::infinity();
  bool has_stops() const noexcept { return stop_low_mm > -std::numeric_limits<double>::infinity() ||
                                           stop_high_mm < std::numeric_limits<double>::infinity(); }
};

// Z's: d_g, and the stops overtravel_mm beyond each end of the travel.
AxisLoad z_axis_load(const ZAxisParams& params) noexcept;

// Rigid stops: a head past one is put at it with speed 0, stuck (then,
// friction on, the Karnopp test decides whether the drive pulls it away);
// each arrival counts once, not each sub-step pressed against it.
class EndStops {
 public:
  explicit EndStops(const AxisLoad& load) noexcept : low_mm_(load.stop_low_mm), high_mm_(load.stop_high_mm) {}
  // True if the state was at or past a stop and was put at it.
  bool apply(AxisState& s) noexcept;
  // A state past a stop (what a block stepped without stops must be redone for).
  bool beyond(const AxisState& s) const noexcept { return s.position_mm > high_mm_ || s.position_mm < low_mm_; }
  std::uint64_t hits() const noexcept { return hits_; }

 private:
  double low_mm_;
  double high_mm_;
  std::uint64_t hits_ = 0;
  bool at_stop_ = false;
};

class ZAxisPlant {
 public:
  // law: Scenario::plant's Z entry ([plant.z] tau_s, friction, ...; kZAxisLaw by default).
  explicit ZAxisPlant(const ZAxisParams& params, const AxisPlantParams& law = kZAxisLaw) noexcept;

  // One 10 us sub-step; disturbance_mm_s is d_cut,z (the process' axial load).
  void step(double command_mm_s, double disturbance_mm_s = 0.0) noexcept;
  // The same law over any duration (tests).
  void step_for(double command_mm_s, double disturbance_mm_s, double duration_s) noexcept;

  double position_mm() const noexcept { return axis_.position_mm(); }
  double speed_mm_s() const noexcept { return axis_.speed_mm_s(); }
  bool stuck() const noexcept { return axis_.stuck(); }
  // The head is outside its travel (between a travel end and its stop).
  bool beyond_travel() const noexcept {
    return axis_.position_mm() > params_.travel_top_mm || axis_.position_mm() < params_.travel_bottom_mm;
  }
  std::uint64_t end_stop_hits() const noexcept { return stops_.hits(); }
  const AxisPlant& axis() const noexcept { return axis_; }
  const ZAxisParams& params() const noexcept { return params_; }

  void set_state(double position_mm, double speed_mm_s, bool stuck = false) noexcept {
    axis_.set_state(position_mm, speed_mm_s, stuck);
  }

 private:
  void stop_at_end_stops() noexcept;

  ZAxisParams params_;
  AxisLoad load_;
  AxisPlant axis_;
  EndStops stops_;
};

}  // namespace tnv::emu
