#pragma once
// A test bench in front of the emulated machine's register door for the
// cutting tests: speed commands through the DACs, the judge's truth back.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "emulator/cutting_disturbance.hpp"
#include "emulator/machine.hpp"
#include "hal/io_board_registers.hpp"

namespace tnv::emu::test_support {

struct TableSample {
  double t_s = 0.0;
  double vx_mm_s = 0.0, vy_mm_s = 0.0;
  double x_mm = 0.0, y_mm = 0.0;
  CuttingVector cut;  // d_cut of the sub-step that ended at the tick
  bool x_stuck = false, y_stuck = false;
};

class CuttingBench {
 public:
  explicit CuttingBench(const Scenario& s)
      : m_(s), lsb_mm_s_(s.dac.rpm_at_full_scale / 60.0 * s.encoder.lead_mm / std::ldexp(1.0, s.dac.bits - 1)) {}
  void enable() {
    command(0.0, 0.0);
    EXPECT_TRUE(m_.write_register(hal::regs::kOutputs, hal::regs::kOutputEnableX | hal::regs::kOutputEnableY));
  }
  // Speed commands in mm/s, rounded to DAC codes.
  void command(double ux_mm_s, double uy_mm_s) {
    EXPECT_TRUE(m_.write_register(hal::regs::kDacX, code(ux_mm_s)));
    EXPECT_TRUE(m_.write_register(hal::regs::kDacY, code(uy_mm_s)));
  }
  TableSample tick() {
    m_.advance_to_next_tick();
    return now();
  }
  TableSample now() const {
    const AxisTruth x = m_.truth(hal::Axis::x), y = m_.truth(hal::Axis::y);
    return {m_.time_s(), x.speed_mm_s, y.speed_mm_s, x.position_mm, y.position_mm,
            {x.cutting_mm_s, y.cutting_mm_s}, x.stuck, y.stuck};
  }
  double lsb_mm_s() const { return lsb_mm_s_; }

 private:
  std::uint32_t code(double u_mm_s) const {
    return static_cast<std::uint32_t>(static_cast<long>(m_.dac_mid_code()) + std::lround(u_mm_s / lsb_mm_s_));
  }
  Machine m_;
  double lsb_mm_s_;
};

}  // namespace tnv::emu::test_support
