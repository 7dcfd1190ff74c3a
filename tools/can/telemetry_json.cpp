#include "tools/can/telemetry_json.hpp"

#include <string>

#include "firmware/can/param_table.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "hal/axis.hpp"

namespace tnv::can_host {

nlohmann::json heartbeat_json(const Heartbeat& hb) {
  nlohmann::json bits = nlohmann::json::array();
  for (const fw::can::HeartbeatBitDoc& b : fw::can::kHeartbeatBits)
    if ((hb.errors & b.mask) != 0) bits.push_back(b.name);
  for (const hal::Axis a : hal::kAxes) {  // HEARTBEAT.axes, named as the errors bits are
    if (hb.homed(a)) bits.push_back(std::string("homed_") + hal::axis_label(a));
    if (hb.shaper_on(a)) bits.push_back(std::string("shaper_") + hal::axis_label(a));
  }
  return {{"state", fw::to_string(hb.state)},
          {"fault", fw::to_string(hb.fault)},
          {"flags", bits},
          {"overruns", hb.overruns},
          {"free_slots", hb.free_slots},
          {"owner", hb.owner}};
}

nlohmann::json spindle_json(const SpindleTelemetry& s) {
  return {{"state", spindle_state(s)},
          {"target_rpm", s.target_rpm},
          {"command_rpm", s.command_rpm},
          {"measured_rpm", s.measured_rpm},
          {"at_speed", s.at_speed()},
          {"commanded_on", s.commanded_on()},
          {"direction", s.reverse() ? "reverse" : "forward"},
          {"inhibited", s.inhibited()},
          {"waiting_feed", (s.flags & fw::can::kSpindleFeedWaiting) != 0},
          {"stop_cause", fw::to_string(s.stop_cause)}};
}

nlohmann::json telemetry_json(const TelemetryView& l, double t_s, double load) {
  nlohmann::json j = {{"t_s", t_s}, {"frames", l.frames}, {"bus_load", load}};
  if (l.heartbeat) j["status"] = heartbeat_json(*l.heartbeat);
  if (l.position_mm) j["position_mm"] = *l.position_mm;
  if (l.following_mm) {
    j["following_um"] = nlohmann::json::array();
    for (const double mm : *l.following_mm) j["following_um"].push_back(mm * 1e3);
  }
  if (l.s_mm_s) j["s_mm_s"] = *l.s_mm_s;
  if (l.d_hat_mm_s) j["d_hat_mm_s"] = *l.d_hat_mm_s;
  if (l.output) {
    j["output"] = {{"force_n", l.output->force_n}};
    for (const hal::Axis a : hal::kAxes)
      j["output"][std::string("dac_") + hal::axis_label(a)] = l.output->dac_code[hal::index(a)];
  }
  if (l.contour) j["contour"] = {{"um", l.contour->contour_um}, {"motion_tick", l.contour->motion_tick}};
  if (l.arsc)
    j["arsc"] = {{"force_n", l.arsc->force_n},
                 {"force_ref_n", l.arsc->force_ref_n},
                 {"feed_override", l.arsc->feed_override},
                 {"cutting_gain_n_per_mm_s", l.arsc->cutting_gain_n_per_mm_s}};
  if (l.spindle) j["spindle"] = spindle_json(*l.spindle);
  return j;
}

}  // namespace tnv::can_host
