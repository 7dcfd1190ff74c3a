#include "emulator/cutting_at_tool.hpp"

namespace tnv::emu {

CuttingAtTool::CuttingAtTool(const Scenario& s, double substep_s) noexcept
    : tool_(s.tool),
      stock_(s.stock),
      probe_(s.probe, stock_),
      force_(s.tool_cut, s.tool, substep_s),
      crashes_(s.tool_cut.crash_speed_fraction) {}

void CuttingAtTool::advance(const ToolPointMotion& at, double spindle_rpm, double commanded_rpm,
                            double time_s) noexcept {
  depth_mm_ = stock_.engagement_mm(at.x_mm, at.y_mm, at.z_mm, tool_);
  crashes_.observe(engaged(), CrashEvent{.time_s = time_s,
                                         .x_mm = at.x_mm,
                                         .y_mm = at.y_mm,
                                         .z_mm = at.z_mm,
                                         .spindle_rpm = spindle_rpm,
                                         .commanded_rpm = commanded_rpm});
  force_.advance(at.vx_mm_s, at.vy_mm_s, depth_mm_, spindle_rpm);
  probe_triggered_ = probe_.triggered(at.x_mm, at.y_mm, at.z_mm);
}

}  // namespace tnv::emu
