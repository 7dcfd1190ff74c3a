#include "tools/hil/shaper_move_run.hpp"

#include <algorithm>
#include <cmath>

#include "emulator/machine.hpp"
#include "firmware/tick/tick_task.hpp"
#include "tools/hil/command_status_text.hpp"
#include "tools/hil/hil_firmware_config.hpp"
#include "tools/hil/hil_rig.hpp"

namespace tnv::hil {

namespace {
}  // namespace

MoveRunResult run_move(const MoveRunRequest& request, const fw::FirmwareConfig& base_config) {
  MoveRunResult result;
  const emu::Scenario& scenario = request.scenario;
  std::unique_ptr<HilRig> rig = HilRig::create(scenario, base_config, request.controller, result.error);
  if (!rig) return result;
  emu::Machine& machine = rig->machine;
  fw::TickTask& task = rig->task;
  const hal::Axis axis = request.move.axis;
  const std::size_t a = hal::index(axis);
  if (request.shaper) {
    if (task.configure_shaper(axis, *request.shaper) != fw::CommandStatus::ok ||
        task.enable_shaper(axis, true) != fw::CommandStatus::ok) {
      result.error = "shaper refused: " + std::string(fw::validate(*request.shaper).field);
      return result;
    }
  }
  rig->home();
  const double start_mm = task.last_record().axis[a].position_mm;
  if (const fw::CommandStatus st = task.start_move(request.move); st != fw::CommandStatus::ok) {
    result.error = "start_move refused: " + command_status_text(st, task) + " (" + fw::validate(request.move) + ")";
    return result;
  }
  const fw::PointToPointMove planned(request.move, start_mm);
  result.move_time_s = planned.duration_s();
  result.target_mm = planned.end_mm();
  result.shaper_delay_s = task.shaper_delay_s(axis);
  result.shaper_duration_s = static_cast<double>(task.shaper(axis).span_samples()) * kTickPeriodS;

  const auto dwell_ticks = static_cast<std::int64_t>(std::llround(request.move.dwell_s / kTickPeriodS));
  const auto motion_ticks = static_cast<std::int64_t>(std::ceil((result.move_time_s + request.window_s) / kTickPeriodS));
  if (request.keep_trace) result.trace.reserve(static_cast<std::size_t>(motion_ticks + 1));
  std::vector<std::pair<double, double>> tool_um;  // (t, tool - target)
  tool_um.reserve(static_cast<std::size_t>(motion_ticks + 1));
  std::optional<double> command_end_s;
  for (std::int64_t k = 0; k < dwell_ticks + motion_ticks; ++k) {
    rig->settle_charge();  // charged time (hil_rig.hpp)
    machine.advance_to_next_tick();
    const emu::AxisTruth truth = machine.truth(axis);  // at this tick's latch
    rig->charged_call([&task]() noexcept { task.tick(); });
    if (task.state() == fw::MotionState::faulted) break;
    const fw::TickRecord& rec = task.last_record();
    if (rec.motion_tick < 0 && !command_end_s && k < dwell_ticks) continue;
    const double t_s = static_cast<double>(k - dwell_ticks) * kTickPeriodS;
    const fw::AxisTickRecord& r = rec.axis[a];
    if (!command_end_s && task.state() == fw::MotionState::holding) command_end_s = t_s;
    result.max_following_error_um =
        std::max(result.max_following_error_um, std::fabs(r.reference_mm - r.position_mm) * 1e3);
    result.max_unshaped_error_um =
        std::max(result.max_unshaped_error_um, std::fabs(r.unshaped_reference_mm - r.position_mm) * 1e3);
    tool_um.emplace_back(t_s, (truth.tool_position_mm - result.target_mm) * 1e3);
    if (request.keep_trace)
      result.trace.push_back(
          {t_s, r.unshaped_reference_mm, r.reference_mm, r.position_mm, truth.position_mm, truth.tool_position_mm});
  }
  result.fault = task.fault();
  if (task.state() == fw::MotionState::faulted) {
    result.error =
        std::string("fault: ") + fw::to_string(result.fault.reason) + " at tick " + std::to_string(result.fault.tick);
    return result;
  }
  if (!command_end_s) {
    result.error = "the move did not come to rest inside the window";
    return result;
  }
  result.command_end_s = *command_end_s;
  double lo = 1e300, hi = -1e300;
  std::optional<double> last_outside_s;
  for (const auto& [t_s, e_um] : tool_um) {
    if (t_s >= result.command_end_s) {
      lo = std::min(lo, e_um);
      hi = std::max(hi, e_um);
    }
    if (std::fabs(e_um) > request.settle_band_um) last_outside_s = t_s;
  }
  result.residual_pp_um = hi - lo;
  result.final_tool_error_um = tool_um.back().second;
  const double end_s = tool_um.back().first;
  if (!last_outside_s) {
    result.settling_s = 0.0;
  } else if (*last_outside_s < end_s) {
    // Whole microseconds: the tick grid is 1 ms, the rest is rounding noise.
    result.settling_s = std::round(std::max(0.0, *last_outside_s + kTickPeriodS - result.move_time_s) * 1e6) / 1e6;
  }
  result.completed = true;
  return result;
}

}  // namespace tnv::hil
