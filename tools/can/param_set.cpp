#include "tools/can/param_set.hpp"

#include <algorithm>
#include <string>

#include "tools/can/param_text.hpp"

namespace tnv::can_host {

namespace can = fw::can;

std::string safety_refusal(const std::vector<ParamAssignment>& changes) {
  std::string names;
  int n = 0;
  for (const ParamAssignment& c : changes)
    if (can::safety_param(*c.param)) {
      names.append(n == 0 ? "" : ", ").append(c.param->name);
      ++n;
    }
  if (n == 0) names = "the set";  // the node saw a change this host did not ask for
  names.append(n > 1 ? " are safety parameters: " : " is a safety parameter: ").append(kEnterCommissioning);
  return names;
}

std::string explain_invalid(NodeClient& client, const std::vector<ParamAssignment>& changes) {
  can::NodeSettings s = can::default_node_settings();
  for (const can::ParamDef& p : can::param_table())
    if (p.access == can::Access::read_write) p.set(s, client.get(p));
  for (const ParamAssignment& c : changes) c.param->set(s, can::from_wire(*c.param, can::to_wire(*c.param, c.requested)));
  const can::SettingsCheck check = can::validate(s);
  if (check.ok) return "";
  std::string out;
  if (const can::ParamDef* p = can::find_param(check.param)) out.append(p->name).append(": ");
  out.append(check.section).append(": ").append(check.reason);
  return out;
}

std::vector<double> stage_params(NodeClient& client, const std::vector<ParamAssignment>& changes) {
  std::vector<double> staged;  // what the node said it staged, per change
  try {
    for (const ParamAssignment& c : changes) staged.push_back(client.stage(*c.param, c.requested));
  } catch (const RequestError& e) {
    if (e.kind() == RequestError::Kind::refused) {
      try {
        client.discard();
      } catch (const std::exception&) {
        // The refusal is what matters; the node drops a stale stage at the next commit anyway.
      }
      if (e.code() == can::ErrorCode::commissioning_required)
        throw RequestError(RequestError::Kind::refused, safety_refusal(changes), e.code());
    }
    throw;
  }
  return staged;
}

std::vector<double> commit_params(NodeClient& client, const std::vector<ParamAssignment>& changes,
                                  const std::vector<double>& staged) {
  std::uint16_t applied = 0;
  try {
    applied = client.commit();
  } catch (const RequestError& e) {
    if (e.kind() != RequestError::Kind::refused) throw;
    std::string message = e.what();
    if (e.code() == can::ErrorCode::commissioning_required) message = safety_refusal(changes);
    if (e.code() == can::ErrorCode::invalid)
      if (const std::string why = explain_invalid(client, changes); !why.empty()) message.append(": ").append(why);
    if (e.code() == can::ErrorCode::busy) {
      std::string idle;
      for (const ParamAssignment& c : changes)
        if (c.param->apply == can::Apply::idle) idle.append(idle.empty() ? "" : ", ").append(c.param->name);
      if (!idle.empty()) message.append(": ").append(idle).append(" can only change at rest (apply: idle)");
    }
    try {
      client.discard();
    } catch (const std::exception&) {
    }
    throw RequestError(RequestError::Kind::refused, message, e.code());
  }
  // The commit must have applied exactly this host's stages, and each must read back as staged.
  std::vector<std::uint16_t> ids;
  for (const ParamAssignment& c : changes)
    if (std::find(ids.begin(), ids.end(), c.param->id) == ids.end()) ids.push_back(c.param->id);
  if (applied != ids.size()) {
    std::string message = "the node's commit applied ";
    message.append(std::to_string(applied)).append(" parameters, this host staged ").append(std::to_string(ids.size()));
    message.append(" (another host's stages, or stages lost): check the values with `params get`");
    throw ParamSetMismatch(message);
  }
  std::vector<double> after;
  for (const ParamAssignment& c : changes) after.push_back(client.get(*c.param));
  for (std::size_t i = 0; i < changes.size() && i < staged.size(); ++i) {
    // A later change of the same parameter wins; compare the last one only.
    bool last = true;
    for (std::size_t j = i + 1; j < changes.size(); ++j) last = last && changes[j].param != changes[i].param;
    if (!last || can::to_wire(*changes[i].param, after[i]) == can::to_wire(*changes[i].param, staged[i])) continue;
    const can::ParamDef& p = *changes[i].param;
    std::string message = "read back ";
    message.append(p.name).append(" = ").append(format_param_value(p, after[i])).append(" after the commit, staged ");
    message.append(format_param_value(p, staged[i])).append(": another host changed it, or the commit did not apply it");
    throw ParamSetMismatch(message);
  }
  return after;
}

}  // namespace tnv::can_host
