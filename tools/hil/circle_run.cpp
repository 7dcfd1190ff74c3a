#include "tools/hil/circle_run.hpp"

#include <cmath>

#include "emulator/machine.hpp"
#include "firmware/tick/tick_task.hpp"
#include "tools/hil/command_status_text.hpp"
#include "tools/hil/hil_firmware_config.hpp"
#include "tools/hil/hil_rig.hpp"

namespace tnv::hil {

CircleRunResult run_circle(const emu::Scenario& scenario, const fw::FirmwareConfig& base_config,
                           fw::ControllerKind controller, const CircleRunOptions& options) {
  CircleRunResult result;
  std::unique_ptr<HilRig> rig = HilRig::create(scenario, base_config, controller, result.error);
  if (!rig) return result;
  emu::Machine& machine = rig->machine;
  fw::TickTask& task = rig->task;
  rig->home();
  if (const fw::CommandStatus st = task.start_circle(circle_spec_for(scenario)); st != fw::CommandStatus::ok) {
    result.error = "start_circle refused: " + command_status_text(st, task);
    return result;
  }

  const double period_s = 1e-3;
  const std::int64_t max_ticks = task.motion_ticks() + static_cast<std::int64_t>(scenario.circle.dwell_s / period_s) + 100;
  if (options.keep_trace) result.trace.reserve(static_cast<std::size_t>(task.motion_ticks() + 1));
  ContourAccumulator contour, true_table, true_tool;
  for (std::int64_t k = 0; k < max_ticks; ++k) {
    rig->tick();
    const fw::TickRecord& rec = task.last_record();
    if (task.state() == fw::MotionState::faulted) break;
    if (rec.motion_tick >= 0) {
      const auto& ax = rec.axis[0];
      const auto& ay = rec.axis[1];
      // The three errors share the reference's radius, and the tool's is the
      // table's when no structural mode deflects it (the same bits, computed once).
      const double reference_radius_mm = radius_mm(ax.reference_mm, ay.reference_mm);
      const double e_mm = contour_error_mm(reference_radius_mm, radius_mm(ax.position_mm, ay.position_mm));
      contour.add(e_mm);
      const emu::AxisTruth tx = machine.truth(hal::kPlaneFirst), ty = machine.truth(hal::kPlaneSecond);
      const double table_radius_mm = radius_mm(tx.position_mm, ty.position_mm);
      const bool tool_on_table = tx.tool_position_mm == tx.position_mm && ty.tool_position_mm == ty.position_mm;
      true_table.add(contour_error_mm(reference_radius_mm, table_radius_mm));
      const double tool_radius_mm =
          tool_on_table ? table_radius_mm : radius_mm(tx.tool_position_mm, ty.tool_position_mm);
      true_tool.add(contour_error_mm(reference_radius_mm, tool_radius_mm));
      if (options.keep_trace) {
        TraceSample t;
        t.t_s = static_cast<double>(rec.motion_tick) * period_s;
        for (std::size_t i = 0; i < 2; ++i) {
          const auto& a = rec.axis[i];
          t.reference_mm[i] = a.reference_mm;
          t.position_mm[i] = a.position_mm;
          t.command_mm_s[i] = a.command_mm_s;
          t.s[i] = a.s;
          t.d_hat_mm_s[i] = a.d_hat_mm_s;
          const emu::AxisTruth truth = i == 0 ? tx : ty;
          t.tool_mm[i] = truth.tool_position_mm;
          t.table_mm[i] = truth.position_mm;
        }
        t.contour_um = e_mm * 1000.0;
        result.trace.push_back(t);
      }
    }
    if (task.state() == fw::MotionState::holding) break;
  }
  result.stats = contour.stats();
  result.true_table_stats = true_table.stats();
  result.true_tool_stats = true_tool.stats();
  result.fault = task.fault();
  result.counters = task.counters();
  if (task.state() == fw::MotionState::faulted) {
    result.error = std::string("fault: ") + fw::to_string(result.fault.reason) + " on axis " +
                   (result.fault.axis == 0 ? "x" : result.fault.axis == 1 ? "y" : "-") + " at tick " +
                   std::to_string(result.fault.tick);
  } else if (task.state() != fw::MotionState::holding) {
    result.timed_out = true;
    result.error = "the circle did not finish in the expected time";
  } else {
    result.completed = true;
  }
  return result;
}

}  // namespace tnv::hil
