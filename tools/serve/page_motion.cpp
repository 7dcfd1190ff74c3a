#include "tools/serve/page_motion.hpp"

#include <cmath>

#include "hal/axis_choice.hpp"
#include "tools/can/motion_run.hpp"
#include "tools/serve/api_error.hpp"
#include "tools/serve/node_refusal.hpp"

namespace tnv::serve {

namespace {

double number(const nlohmann::json& body, const char* key, double fallback, double max) {
  if (!body.contains(key)) return fallback;
  if (!body[key].is_number()) throw ApiError(kHttpBadRequest, std::string(key) + " must be a number");
  const double v = body[key].get<double>();
  if (!std::isfinite(v) || std::fabs(v) > max) {
    char buf[120];
    std::snprintf(buf, sizeof buf, "%s must be finite and within +/-%g (got %g)", key, max, v);
    throw ApiError(kHttpBadRequest, buf);
  }
  return v;
}

}  // namespace

MotionRequest parse_motion_request(const nlohmann::json& body, const can_host::EmulatedBus* emulated) {
  if (!body.is_object() || !body.contains("kind") || !body["kind"].is_string())
    throw ApiError(kHttpBadRequest, "give \"kind\": enable, disable, circle, move, stop or estop");
  MotionRequest r;
  r.kind = body["kind"].get<std::string>();
  if (r.kind == "circle") {
    r.radius_mm = number(body, "radius_mm", emulated ? emulated->scenario().circle.radius_mm : 6.0, 1000.0);
    r.feed_mm_s = number(body, "feed_mm_s", emulated ? emulated->scenario().circle.feed_mm_s : 2.0, 1000.0);
    if (r.radius_mm <= 0.0 || r.feed_mm_s <= 0.0) throw ApiError(kHttpBadRequest, "radius_mm and feed_mm_s must be > 0");
  } else if (r.kind == "move") {
    const std::string axis = body.value("axis", std::string("x"));
    if (!hal::axis_from_name(axis)) throw ApiError(kHttpBadRequest, "axis must be " + std::string(hal::kQuotedAxisChoices));
    r.axis = axis == "x" ? 0 : 1;
    r.distance_mm = number(body, "distance_mm", 0.0, 10000.0);
    r.speed_mm_s = number(body, "speed_mm_s", 0.0, 655.35);  // the MOVE frame's range
    if (r.distance_mm == 0.0 || r.speed_mm_s <= 0.0)
      throw ApiError(kHttpBadRequest, "move: distance_mm must not be 0 and speed_mm_s must be > 0");
  } else if (r.kind != "stop" && r.kind != "estop" && r.kind != "enable" && r.kind != "disable") {
    throw ApiError(kHttpBadRequest, "unknown motion '" + r.kind + "': enable, disable, circle, move, stop or estop");
  }
  return r;
}

nlohmann::json start_motion(can_host::NodeClient& client, const MotionRequest& r) {
  return refusals_as_conflict([&]() -> nlohmann::json {
    if (r.kind == "estop") {
      client.estop(false);  // never acknowledged: the heartbeat shows it
      return {{"kind", r.kind}};
    }
    can_host::CommandAck ack;
    if (r.kind == "circle") ack = client.circle(r.radius_mm, r.feed_mm_s);
    else if (r.kind == "move") ack = client.move(r.axis, r.distance_mm, r.speed_mm_s);
    else if (r.kind == "enable") ack = client.command(fw::can::CommandCode::enable);
    else if (r.kind == "disable") ack = client.command(fw::can::CommandCode::disable);
    else ack = client.command(fw::can::CommandCode::stop);
    return {{"kind", r.kind}, {"state", fw::to_string(ack.state)}};
  });
}

nlohmann::json clear_faults_for_page(can_host::NodeClient& client) {
  return refusals_as_conflict([&]() -> nlohmann::json {
    bool retried = false;
    const can_host::CommandAck ack = can_host::clear_faults(client, retried);
    return {{"state", fw::to_string(ack.state)}, {"retried", retried}};
  });
}

}  // namespace tnv::serve
