#pragma once
// The parameter table as the page edits it: list (value, unit, range,
// staged value), stage one change at a time, commit the staged set (all or
// nothing), discard it, or set one value (stage + commit). The checks,
// the commit and the refusal reasons are tools/can/param_set's, as
// `tnvctl params set` uses them. Used on the node thread only.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/can/node_client.hpp"
#include "tools/can/param_set.hpp"

namespace tnv::serve {

class ParamDesk {
 public:
  // Every parameter whose name contains `filter`:
  // [{"name", "id", "value", "text", "unit", "range", "access", "apply", "safety", "doc", "staged"?}].
  nlohmann::json list(can_host::NodeClient& client, const std::string& filter) const;

  // The change checked against the table (name, type, range) before
  // anything is sent: ApiError(400) naming what is wrong. `value` is a
  // number or a string ("rdvsc", "on", "0.25").
  static can_host::ParamAssignment parse(const std::string& name, const nlohmann::json& value);

  // Stages one change; a refusal discards this host's whole staged set
  // (the node's rule) and throws ApiError(409) with the reason.
  nlohmann::json stage(can_host::NodeClient& client, const std::string& name, const nlohmann::json& value);
  // Commits the staged set: {"applied": [{"name", "value", "text"}...]}; a
  // refusal (ApiError 409, the reason named) leaves every value as it was.
  nlohmann::json commit(can_host::NodeClient& client);
  nlohmann::json discard(can_host::NodeClient& client);
  // One value staged and committed; refused (409) while a staged set waits.
  nlohmann::json set(can_host::NodeClient& client, const std::string& name, const nlohmann::json& value);

  // {"name": staged value text} of what this host has staged.
  nlohmann::json staged_json() const;

 private:
  std::vector<can_host::ParamAssignment> changes_;
  std::vector<double> staged_;  // what the node read back per change
};

}  // namespace tnv::serve
