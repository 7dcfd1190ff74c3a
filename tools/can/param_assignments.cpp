#include "tools/can/param_assignments.hpp"

#include "firmware/can/node_settings.hpp"
#include "firmware/can/param_table.hpp"
#include "tools/can/param_text.hpp"

namespace tnv::can_host {

NodeAssignmentsResult node_settings_from_assignments(const std::vector<std::string>& assignments,
                                                     const fw::can::NodeSettings& base) {
  fw::can::NodeSettings settings = base;
  for (const std::string& a : assignments) {
    const auto eq = a.find('=');
    const fw::can::ParamDef* p = eq == std::string::npos ? nullptr : find_param_by_text(a.substr(0, eq));
    if (p == nullptr || p->access != fw::can::Access::read_write)
      return {std::nullopt, a + ": expected NAME=VALUE with a writable parameter (tnvctl params list)"};
    std::string error;
    const std::optional<double> v = parse_param_value(*p, a.substr(eq + 1), error);
    if (!v) return {std::nullopt, error};
    p->set(settings, *v);
  }
  if (const fw::can::SettingsCheck check = fw::can::validate(settings); !check.ok)
    return {std::nullopt, std::string(check.section) + ": " + check.reason};
  return {settings, {}};
}

AssignmentsResult firmware_config_from_assignments(const std::vector<std::string>& assignments) {
  NodeAssignmentsResult r = node_settings_from_assignments(assignments, fw::can::default_node_settings());
  if (!r.settings) return {std::nullopt, std::move(r.error)};
  return {r.settings->firmware, {}};
}

}  // namespace tnv::can_host
