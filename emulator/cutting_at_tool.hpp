#pragma once
// The process where the tool is, one 10 us sub-step at a time: the stock
// block, the milling force of the engagement there, the crash rule and the
// touch probe, from the tool point's motion and the spindle's speeds. The
// spindle's load (force_n) and the XY disturbances go back to the plants.
#include "emulator/scenario.hpp"
#include "emulator/spindle_crash_log.hpp"
#include "emulator/stock_block.hpp"
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
  CuttingAtTool(const Scenario& scenario, double substep_s) noexcept;
  CuttingAtTool(const CuttingAtTool&) = delete;  // the probe refers to this object's stock
  CuttingAtTool& operator=(const CuttingAtTool&) = delete;

  void advance(const ToolPointMotion& at, double spindle_rpm, double commanded_rpm, double time_s) noexcept;

  double depth_mm() const noexcept { return depth_mm_; }  // a_p now
  bool engaged() const noexcept { return depth_mm_ > 0.0; }
  bool probe_triggered() const noexcept { return probe_triggered_; }
  // The probe against this stock at a tool point (emu::Machine samples it at each tick latch).
  bool probe_touches(double x_mm, double y_mm, double z_mm) const noexcept { return probe_.triggered(x_mm, y_mm, z_mm); }
  const ToolMillingForce& force() const noexcept { return force_; }
  const SpindleCrashLog& crashes() const noexcept { return crashes_; }
  const StockBlock& stock() const noexcept { return stock_; }

 private:
  ToolParams tool_;
  StockBlock stock_;
  TouchProbe probe_;
  ToolMillingForce force_;
  SpindleCrashLog crashes_;
  double depth_mm_ = 0.0;
  bool probe_triggered_ = false;
};

}  // namespace tnv::emu
