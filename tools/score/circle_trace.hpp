#pragma once
// One sample of an S1 circle trace: what tnv-hil records on the rig
// (tools/hil/circle_run.hpp) and tnvctl rebuilds from a capture
// (tools/can/capture_score.hpp), drawn by the same circle figure.
#include <array>

namespace tnv::hil {

struct TraceSample {
  double t_s = 0.0;  // since the start of motion
  std::array<double, 2> reference_mm{};
  std::array<double, 2> position_mm{};  // encoder-measured, as scored
  std::array<double, 2> command_mm_s{};
  std::array<double, 2> s{};
  std::array<double, 2> d_hat_mm_s{};
  std::array<double, 2> tool_mm{};      // emulator truth (tool point)
  std::array<double, 2> table_mm{};     // emulator truth (table: the motor side through the ball screw)
  double contour_um = 0.0;
};

}  // namespace tnv::hil
