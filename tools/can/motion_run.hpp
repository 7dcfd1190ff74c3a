#pragma once
// Motions as a host runs them to the end: how long each should take from
// the node's parameters, and the wait for rest that turns a fault into an
// error naming it.
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include "hal/axis.hpp"
#include "tools/can/node_client.hpp"

namespace tnv::can_host {

// COMMAND's axis value for every axis.
inline constexpr std::uint8_t kAllAxes = 255;

// The node ended a motion in a fault, or a cycle did not reach its goal.
class MotionFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Dwell, ramps and cruise of a point-to-point move / the circle (seconds).
double move_expected_s(NodeClient& client, double distance_mm, double speed_mm_s);
double circle_expected_s(NodeClient& client, double radius_mm, double feed_mm_s);
// The longest a homing cycle of the axes can take (search and latch travels at their speeds).
// axis: an axis' index, or kAllAxes.
double homing_bound_s(NodeClient& client, std::uint8_t axis);

// "<axis> is not homed ..." for the first of the axes asked for (an index or
// kAllAxes) the heartbeat does not show homed; none when all are.
std::optional<std::string> not_homed_message(const Heartbeat& hb, std::uint8_t axis);

// "<what> ended in a fault: <reason> on axis x (value .., tick ...n); ..."
// when `hb` shows a fault, else nullopt.
std::optional<std::string> fault_message(const Heartbeat& hb, NodeClient& client, const std::string& what);

// Until a heartbeat shows the motion is over, waited up to 1.5 x
// `expected_s` + 5 s; throws MotionFailed when it ended in a fault.
Heartbeat wait_motion_done(NodeClient& client, const std::string& what, double expected_s);

// COMMAND clear_faults; a board trip takes two clears (the first resets the
// board's latch and is refused with cause_present), so one retry 5 ms
// later. `retried` tells whether it was needed.
CommandAck clear_faults(NodeClient& client, bool& retried);

}  // namespace tnv::can_host
