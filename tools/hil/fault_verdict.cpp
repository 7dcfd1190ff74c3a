#include "tools/hil/fault_verdict.hpp"

#include <string>

#include "hal/axis_choice.hpp"

namespace tnv::hil {

bool every_command_zero(const std::array<double, hal::kAxisCount>& command_mm_s) noexcept {
  for (const double v : command_mm_s)
    if (v != 0.0) return false;
  return true;
}

bool fault_case_met(const FaultCase& c, const FaultObservation& o, std::uint32_t mid_code) {
  if (!o.error.empty()) return false;
  if (c.expected == fw::FaultReason::none) return !o.detected && o.live_before_detection;
  const bool reason_ok =
      o.fault.reason == c.expected || (c.also_accepted != fw::FaultReason::none && o.fault.reason == c.also_accepted);
  return o.detected && reason_ok && o.fault.tick == o.latching_tick && o.after_latch.safe(mid_code) &&
         every_command_zero(o.command_after_mm_s);
}

const char* latched_text(const FaultObservation& o) noexcept { return o.detected ? fw::to_string(o.fault.reason) : "none"; }

nlohmann::json fault_case_json(const FaultCase& c, const FaultObservation& obs, bool met) {
  const std::string axis = obs.fault.axis < 0 ? "-" : std::string(hal::axis_label_or(obs.fault.axis, "?"));
  nlohmann::json row = {{"name", c.name},
                        {"motion", to_string(c.motion)},
                        {"expected", fw::to_string(c.expected)},
                        {"latched", latched_text(obs)},
                        {"axis", axis},
                        {"injected_s", obs.injected_s},
                        {"ticks_to_detect", obs.ticks_to_detect()},
                        {"latching_tick", obs.latching_tick},
                        {"fault_tick", obs.fault.tick},
                        {"watchdog_tripped", obs.watchdog_tripped},
                        {"deviation_um", obs.deviation_um},
                        {"missed_ticks", obs.counters.missed_ticks},
                        {"late_ticks", obs.counters.late_ticks},
                        {"note", c.note},
                        {"ok", met}};
  row["time_to_safe_ms"] = obs.time_to_safe_s() ? nlohmann::json(*obs.time_to_safe_s() * 1e3) : nlohmann::json();
  if (obs.detected) {
    nlohmann::json& after = row["after_latch"];
    for (const hal::Axis a : hal::kAxes) {
      after[std::string("dac_") + hal::axis_label(a)] = obs.after_latch.dac_register[hal::index(a)];
      after[std::string("enable_") + hal::axis_label(a)] = obs.after_latch.enabled[hal::index(a)];
    }
  }
  if (!obs.error.empty()) row["error"] = obs.error;
  return row;
}

}  // namespace tnv::hil
