#include "tools/hil/shaper_jog_run.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>
#include <vector>

#include "emulator/machine.hpp"
#include "firmware/tick/tick_task.hpp"
#include "tools/hil/hil_firmware_config.hpp"
#include "tools/hil/hil_rig.hpp"

namespace tnv::hil {

namespace {
constexpr double kLongestStreamS = 600.0;

bool parse_number(const std::string& field, double& out) {
  std::size_t used = 0;
  try {
    out = std::stod(field, &used);
  } catch (...) {
    return false;
  }
  while (used < field.size() && (field[used] == ' ' || field[used] == '\r')) ++used;
  return used == field.size() && std::isfinite(out);
}
}  // namespace

std::string jog_csv_header() {
  std::string h = "t_s";
  for (const hal::Axis a : hal::kAxes) h += std::string(",") + hal::axis_label(a) + "_mm_s";
  return h;
}

std::optional<std::vector<JogCommand>> parse_jog_csv(const std::string& text, std::string& error) {
  constexpr std::size_t kFields = 1 + hal::kAxisCount;  // t_s, then a speed per axis
  const std::string header_text = jog_csv_header();
  std::vector<std::string> names{"t_s"};
  for (const hal::Axis a : hal::kAxes) names.push_back(std::string(hal::axis_label(a)) + "_mm_s");
  std::vector<JogCommand> out;
  std::istringstream in(text);
  std::string line;
  int n = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      if (line != header_text) {
        error = "line " + std::to_string(n) + ": header must be " + header_text;
        return std::nullopt;
      }
      header = true;
      continue;
    }
    std::vector<std::string> fields;
    std::string f;
    std::istringstream row(line);
    while (std::getline(row, f, ',')) fields.push_back(f);
    if (fields.size() != kFields) {
      error = "line " + std::to_string(n) + ": expected " + std::to_string(kFields) + " fields (" + header_text +
              "), got " + std::to_string(fields.size());
      return std::nullopt;
    }
    std::array<double, kFields> v{};
    for (std::size_t i = 0; i < kFields; ++i)
      if (!parse_number(fields[i], v[i])) {
        error = "line " + std::to_string(n) + ": " + names[i] + " is not a finite number";
        return std::nullopt;
      }
    if (v[0] < 0.0 || v[0] > kLongestStreamS || (!out.empty() && v[0] <= out.back().t_s)) {
      error = "line " + std::to_string(n) + ": t_s must increase, 0.." +
              std::to_string(static_cast<int>(kLongestStreamS)) + " s";
      return std::nullopt;
    }
    JogCommand c{v[0], {}};
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) c.speed_mm_s[i] = v[1 + i];
    out.push_back(c);
  }
  if (out.empty()) {
    error = header ? "no command rows" : "empty file (header " + header_text + " expected)";
    return std::nullopt;
  }
  return out;
}

JogRunResult run_jog(const JogRunRequest& request, const fw::FirmwareConfig& base_config) {
  JogRunResult result;
  const emu::Scenario& scenario = request.scenario;
  if (request.commands.empty()) {
    result.error = "no jog commands";
    return result;
  }
  std::unique_ptr<HilRig> rig = HilRig::create(scenario, base_config, request.controller, result.error);
  if (!rig) return result;
  emu::Machine& machine = rig->machine;
  fw::TickTask& task = rig->task;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const hal::Axis axis = hal::axis_from_index(i);
    if (!request.shaper[i]) continue;
    if (task.configure_shaper(axis, *request.shaper[i]) != fw::CommandStatus::ok ||
        task.enable_shaper(axis, true) != fw::CommandStatus::ok) {
      result.error =
          std::string("shaper refused on axis ") + hal::axis_name(axis) + ": " + fw::validate(*request.shaper[i]).field;
      return result;
    }
  }
  rig->home();
  if (task.hold_position() != fw::CommandStatus::ok) {
    result.error = "servo-on refused";
    return result;
  }
  rig->settle_charge();  // charged time (hil_rig.hpp)
  machine.advance_to_next_tick();
  rig->charged_call([&task]() noexcept { task.tick(); });
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    result.axis[i].start_mm = task.last_record().axis[i].reference_mm;
    result.axis[i].shaper_delay_s = task.shaper_delay_s(hal::axis_from_index(i));
  }

  const auto last_row_tick = static_cast<std::int64_t>(std::llround(request.commands.back().t_s / kTickPeriodS));
  const auto window_ticks = static_cast<std::int64_t>(std::llround(request.window_s / kTickPeriodS));
  std::int64_t stop_tick = -1;  // first tick of the final rest, -1 while moving
  std::size_t row = 0;
  std::vector<std::array<double, 1 + hal::kAxisCount>> tool_samples;  // t, then the tool point per axis
  for (std::int64_t k = 0;; ++k) {
    const double t_s = static_cast<double>(k) * kTickPeriodS;
    // The pendant: hold the current row, silent after the last one.
    while (row + 1 < request.commands.size() && request.commands[row + 1].t_s <= t_s + 1e-9) ++row;
    if (k <= last_row_tick && request.commands[row].t_s <= t_s + 1e-9) {
      for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
        const double v = request.commands[row].speed_mm_s[i];
        const bool axis_idle = v == 0.0 && task.state() != fw::MotionState::moving;
        if (axis_idle) continue;  // nothing to send for a standing axis
        if (task.jog(hal::axis_from_index(i), v) != fw::CommandStatus::ok) ++result.refused_commands;
      }
    }
    rig->settle_charge();  // charged time (hil_rig.hpp)
    machine.advance_to_next_tick();
    std::array<double, 1 + hal::kAxisCount> tool{t_s};  // the tool point where the sub-steps left it
    for (const hal::Axis axis : hal::kAxes) tool[1 + hal::index(axis)] = machine.truth(axis).tool_position_mm;
    rig->charged_call([&task]() noexcept { task.tick(); });
    if (task.state() == fw::MotionState::faulted) break;
    const fw::TickRecord& rec = task.last_record();
    tool_samples.push_back(tool);
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      const fw::AxisTickRecord& r = rec.axis[i];
      result.axis[i].max_following_error_um =
          std::max(result.axis[i].max_following_error_um, std::fabs(r.reference_mm - r.position_mm) * 1e3);
    }
    if (request.keep_trace) {
      JogTraceSample q{.t_s = t_s};
      for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
        q.unshaped_mm[i] = rec.axis[i].unshaped_reference_mm;
        q.reference_mm[i] = rec.axis[i].reference_mm;
        q.tool_mm[i] = tool[1 + i];
      }
      result.trace.push_back(q);
    }
    const bool at_rest = task.state() == fw::MotionState::holding;
    if (k > last_row_tick && at_rest && stop_tick < 0) stop_tick = k;
    if (!at_rest) stop_tick = -1;
    if (stop_tick >= 0 && k >= stop_tick + window_ticks) break;
    if (t_s > kLongestStreamS + 60.0) break;
  }
  result.deadman_stops = task.jog_deadman_stops();
  if (task.state() == fw::MotionState::faulted) {
    result.error =
        std::string("fault: ") + fw::to_string(task.fault().reason) + " at tick " + std::to_string(task.fault().tick) +
        " (axis " + std::to_string(task.fault().axis) + ", " + std::to_string(task.fault().value) + ")";
    return result;
  }
  if (stop_tick < 0) {
    result.error = "the axes did not come to rest";
    return result;
  }
  result.stop_s = static_cast<double>(stop_tick) * kTickPeriodS;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    JogAxisResult& a = result.axis[i];
    a.end_mm = task.last_record().axis[i].reference_mm;
    a.unshaped_end_mm = task.last_record().axis[i].unshaped_reference_mm;
    double lo = 1e300, hi = -1e300;
    std::optional<double> last_outside_s;
    for (const auto& s : tool_samples) {
      const double e_um = (s[1 + i] - a.end_mm) * 1e3;
      if (s[0] >= result.stop_s) {
        lo = std::min(lo, e_um);
        hi = std::max(hi, e_um);
      }
      if (std::fabs(e_um) > request.settle_band_um) last_outside_s = s[0];
    }
    a.residual_pp_um = hi - lo;
    if (!last_outside_s || *last_outside_s < tool_samples.back()[0])
      a.settling_s = std::round(std::max(0.0, last_outside_s.value_or(0.0) + kTickPeriodS - result.stop_s) * 1e6) / 1e6;
  }
  result.completed = true;
  return result;
}

}  // namespace tnv::hil
