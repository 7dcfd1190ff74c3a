#pragma once
// The S3 end-milling force on the emulated TNV-40 (scenario [milling]),
// eq. (28) in continuous time and physical units, on the X axis:
//   T_f df/dt = -f + K delta(t) max(v_x, 0)          f in N, v_x in mm/s, delta in mm
// and, as the -f term of eq. (27), a table-speed disturbance opposing the
// feed: d_x = -feed_load f. Integrated exactly over each 10 us sub-step
// with v_x and delta held at their sub-step start values (as the plant
// holds its inputs). A chip cannot have negative thickness: no force while
// the table moves backwards (max(v, 0)). delta(t) follows the depth
// profile in machine time (since construction), S3 Fig. 4.
#include "emulator/scenario.hpp"

namespace tnv::emu {

class MillingForce {
 public:
  MillingForce(const MillingParams& params, double substep_s) noexcept;

  bool enabled() const noexcept { return enabled_; }
  double force_n() const noexcept { return force_n_; }
  double disturbance_mm_s() const noexcept { return -feed_load_ * force_n_; }
  double depth_mm(double time_s) const noexcept;

  // One sub-step starting at time_s with table speed speed_mm_s.
  void advance(double speed_mm_s, double time_s) noexcept;

 private:
  bool enabled_;
  MillingParams params_;
  double decay_;     // exp(-h / T_f)
  double feed_load_;
  double force_n_ = 0.0;
};

}  // namespace tnv::emu
