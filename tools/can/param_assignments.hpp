#pragma once
// NAME=VALUE firmware parameters (the node's names and ranges:
// "x.screw.backlash_um=10") on top of the default node settings, the whole
// set validated: what `tnv-hil ... --set` and a campaign's [vary]
// parameters apply. Nothing is half-applied: on error no config.
#include <optional>
#include <string>
#include <vector>

#include "firmware/can/node_settings.hpp"
#include "firmware/tick/firmware_config.hpp"

namespace tnv::can_host {

struct AssignmentsResult {
  std::optional<fw::FirmwareConfig> config;
  std::string error;  // one line naming the assignment (or the settings section) at fault
};

AssignmentsResult firmware_config_from_assignments(const std::vector<std::string>& assignments);

// The same on top of `base` (an experiment's own settings, e.g. homing's),
// giving the whole node settings: the firmware and the boring planner's.
struct NodeAssignmentsResult {
  std::optional<fw::can::NodeSettings> settings;
  std::string error;
};
NodeAssignmentsResult node_settings_from_assignments(const std::vector<std::string>& assignments,
                                                     const fw::can::NodeSettings& base);

}  // namespace tnv::can_host
