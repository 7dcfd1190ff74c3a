#pragma once
// The touch-probe input (for G38): true while the probe's tip, a ball of
// tip_radius_mm around the tool point (0: the point itself), touches the
// stock, top face or side, or is pushed into it.
#include "emulator/scenario.hpp"
#include "emulator/stock_block.hpp"

namespace tnv::emu {

class TouchProbe {
 public:
  TouchProbe(const ProbeParams& params, const StockBlock& stock) noexcept : params_(params), stock_(stock) {}

  bool triggered(double x_mm, double y_mm, double z_mm) const noexcept {
    return stock_.distance_mm(x_mm, y_mm, z_mm) <= params_.tip_radius_mm;
  }

 private:
  ProbeParams params_;
  const StockBlock& stock_;
};

}  // namespace tnv::emu
