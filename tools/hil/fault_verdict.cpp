#include "tools/hil/fault_verdict.hpp"

#include <string>

#include "hal/axis_choice.hpp"

namespace tnv::hil {

bool fault_case_met(const FaultCase& c, const FaultObservation& o, std::uint32_t mid_code) {
  if (!o.error.empty()) return false;
  if (c.expected == fw::FaultReason::none) return !o.detected && o.live_before_detection;
  const bool reason_ok =
      o.fault.reason == c.expected || (c.also_accepted != fw::FaultReason::none && o.fault.reason == c.also_accepted);
  return o.detected && reason_ok && o.fault.tick == o.latching_tick && o.after_latch.safe(mid_code) &&
         o.command_after_mm_s[0] == 0.0 && o.command_after_mm_s[1] == 0.0;
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
    row["after_latch"] = {{"dac_x", obs.after_latch.dac_register[0]},
                          {"dac_y", obs.after_latch.dac_register[1]},
                          {"enable_x", obs.after_latch.enabled[0]},
                          {"enable_y", obs.after_latch.enabled[1]}};
  }
  if (!obs.error.empty()) row["error"] = obs.error;
  return row;
}

}  // namespace tnv::hil
