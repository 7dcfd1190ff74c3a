#include "tools/serve/param_desk.hpp"

#include <cstdio>

#include "tools/can/param_text.hpp"
#include "tools/can/request_error.hpp"
#include "tools/serve/api_error.hpp"
#include "tools/serve/node_refusal.hpp"

namespace tnv::serve {

namespace {

namespace can = fw::can;
using can_host::format_param_value;

nlohmann::json applied_json(const can::ParamDef& p, double v) {
  return {{"name", p.name}, {"value", v}, {"text", format_param_value(p, v)}};
}

}  // namespace

nlohmann::json ParamDesk::list(can_host::NodeClient& client, const std::string& filter) const {
  nlohmann::json out = nlohmann::json::array();
  for (const can::ParamDef& p : can::param_table()) {
    if (!filter.empty() && std::string(p.name).find(filter) == std::string::npos) continue;
    const double v = client.get(p);
    nlohmann::json j = {{"name", p.name},
                        {"id", p.id},
                        {"value", v},
                        {"text", format_param_value(p, v)},
                        {"unit", p.unit},
                        {"range", can_host::range_text(p)},
                        {"access", can::to_string(p.access)},
                        {"apply", can::to_string(p.apply)},
                        {"safety", can::safety_param(p)},
                        {"doc", p.doc}};
    for (std::size_t i = 0; i < changes_.size(); ++i)
      if (changes_[i].param == &p) j["staged"] = format_param_value(p, staged_[i]);
    out.push_back(std::move(j));
  }
  return out;
}

can_host::ParamAssignment ParamDesk::parse(const std::string& name, const nlohmann::json& value) {
  const can::ParamDef* p = can_host::find_param_by_text(name);
  if (p == nullptr) {
    std::string message = "no parameter named '";
    message.append(name).append("'");
    if (const std::string close = can_host::closest_param_name(name); !close.empty())
      message.append(" (did you mean ").append(close).append("?)");
    throw ApiError(kHttpBadRequest, message);
  }
  std::string text;
  if (value.is_string()) {
    text = value.get<std::string>();
  } else if (value.is_number()) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", value.get<double>());
    text = buf;
  } else if (value.is_boolean()) {
    text = value.get<bool>() ? "on" : "off";
  } else {
    throw ApiError(kHttpBadRequest, std::string(p->name) + ": the value must be a number or a name");
  }
  std::string error;
  const std::optional<double> v = can_host::parse_param_value(*p, text, error);
  if (!v) throw ApiError(kHttpBadRequest, error);
  return {p, *v};
}

nlohmann::json ParamDesk::stage(can_host::NodeClient& client, const std::string& name, const nlohmann::json& value) {
  const can_host::ParamAssignment change = parse(name, value);
  std::vector<can_host::ParamAssignment> one{change};
  const std::vector<double> staged = refusals_as_conflict([&] {
    try {
      return can_host::stage_params(client, one);
    } catch (const can_host::RequestError& e) {
      // stage_params discarded the node's staged set: ours is gone too.
      if (e.kind() == can_host::RequestError::Kind::refused) {
        changes_.clear();
        staged_.clear();
      }
      throw;
    }
  });
  for (std::size_t i = 0; i < changes_.size(); ++i)
    if (changes_[i].param == change.param) {  // staged again: the new value replaces the old
      changes_.erase(changes_.begin() + static_cast<std::ptrdiff_t>(i));
      staged_.erase(staged_.begin() + static_cast<std::ptrdiff_t>(i));
      break;
    }
  changes_.push_back(change);
  staged_.push_back(staged.front());
  return {{"staged", staged_json()}};
}

nlohmann::json ParamDesk::commit(can_host::NodeClient& client) {
  if (changes_.empty()) throw ApiError(kHttpBadRequest, "nothing is staged");
  const std::vector<can_host::ParamAssignment> changes = changes_;
  const std::vector<double> staged = staged_;
  // Whatever the outcome, the node's staged set is gone (applied or discarded).
  changes_.clear();
  staged_.clear();
  const std::vector<double> after =
      refusals_as_conflict([&] { return can_host::commit_params(client, changes, staged); });
  nlohmann::json applied = nlohmann::json::array();
  for (std::size_t i = 0; i < changes.size(); ++i) applied.push_back(applied_json(*changes[i].param, after[i]));
  return {{"applied", applied}};
}

nlohmann::json ParamDesk::discard(can_host::NodeClient& client) {
  client.discard();
  changes_.clear();
  staged_.clear();
  return {{"staged", staged_json()}};
}

nlohmann::json ParamDesk::set(can_host::NodeClient& client, const std::string& name, const nlohmann::json& value) {
  const can_host::ParamAssignment change = parse(name, value);
  if (!changes_.empty()) {
    std::string message = std::to_string(changes_.size());
    message.append(changes_.size() == 1 ? " staged change waits" : " staged changes wait")
        .append(": commit or discard them first");
    throw ApiError(kHttpConflict, message);
  }
  const std::vector<can_host::ParamAssignment> one{change};
  const std::vector<double> after = refusals_as_conflict([&] {
    const std::vector<double> staged = can_host::stage_params(client, one);
    return can_host::commit_params(client, one, staged);
  });
  return {{"applied", nlohmann::json::array({applied_json(*change.param, after.front())})}};
}

nlohmann::json ParamDesk::staged_json() const {
  nlohmann::json out = nlohmann::json::object();
  for (std::size_t i = 0; i < changes_.size(); ++i)
    out[changes_[i].param->name] = format_param_value(*changes_[i].param, staged_[i]);
  return out;
}

}  // namespace tnv::serve
