#pragma once
// The process where the tool is, one 10 us sub-step at a time: the stock
// (its block and the height field the tool cuts), the milling force of the
// engagement there, the crash rule and the touch probe, from the tool
// point's motion and the spindle's speeds. The spindle's load (force_n)
// and the XY disturbances go back to the plants.
#include <array>
#include <cstddef>
#include <limits>

#include "emulator/scenario.hpp"
#include "emulator/spindle_crash_log.hpp"
#include "emulator/stock_block.hpp"
#include "emulator/stock_surface.hpp"
#include "emulator/tool_milling_force.hpp"
#include "emulator/touch_probe.hpp"

namespace tnv::emu {

struct ToolPointMotion {
  double x_mm = 0.0;  // tool point, machine coordinates
  double y_mm = 0.0;
  double z_mm = 0.0;
  double vx_mm_s = 0.0;  // the table's XY speed
  double vy_mm_s = 0.0;
};

// The tool point below a spindle nose at z_nose (reference plant: a rigid tool).
inline double tool_point_z_mm(double nose_z_mm, const ToolParams& tool) noexcept { return nose_z_mm - tool.length_mm; }

class CuttingAtTool {
 public:
  CuttingAtTool(const Scenario& scenario, double substep_s);
  CuttingAtTool(const CuttingAtTool&) = delete;  // the probe refers to this object's stock
  CuttingAtTool& operator=(const CuttingAtTool&) = delete;

  void advance(const ToolPointMotion& at, double spindle_rpm, double commanded_rpm, double time_s) noexcept;

  double depth_mm() const noexcept { return depth_mm_; }  // a_p now
  bool engaged() const noexcept { return depth_mm_ > 0.0; }
  // The probe against this stock at a tool point (emu::Machine samples it at
  // each tick latch): the block's sides, and over it the cut surface under the tip's centre.
  bool probe_touches(double x_mm, double y_mm, double z_mm) const noexcept;
  const ToolMillingForce& force() const noexcept { return force_; }
  const SpindleCrashLog& crashes() const noexcept { return crashes_; }
  const StockBlock& stock() const noexcept { return stock_; }
  const StockSurface& surface() const noexcept { return surface_; }

 private:
  void look(const ToolPointMotion& at);
  ToolParams tool_;
  StockBlock stock_;
  StockSurface surface_;
  TouchProbe probe_;
  double probe_tip_mm_;
  ToolMillingForce force_;
  SpindleCrashLog crashes_;
  double depth_mm_ = 0.0;
  // The last look at the height field (look()): where it was, and the
  // highest material met there and at the looks before it over the tool's
  // last cell of XY travel (newest at met_next_ - 1).
  struct Met {
    double travel_mm;  // the tool's XY path length at the look
    double top_mm;     // the highest material it met (before taking it)
  };
  static constexpr std::size_t kMetWindow = 128;
  double material_top_mm_ = -std::numeric_limits<double>::infinity();
  double looked_x_mm_ = 0.0, looked_y_mm_ = 0.0;
  double clearance_mm_ = 0.0;  // the XY travel after which a tool that is not engaged looks again
  double travel_mm_ = 0.0;
  std::array<Met, kMetWindow> met_{};
  std::size_t met_next_ = 0, met_count_ = 0;
  bool looked_ = false;
  int substeps_since_look_ = 0;
  int substeps_per_look_;  // 1 ms: how often an engaged tool looks again
};

}  // namespace tnv::emu
