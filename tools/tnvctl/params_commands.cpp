// tnvctl params list | get | set | save | load | defaults
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <set>

#include "firmware/can/param_table.hpp"
#include "tools/can/param_set.hpp"
#include "tools/can/param_text.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

namespace can = fw::can;
using can_host::format_param_value;
using can_host::RequestError;

std::string id_text(std::uint16_t id) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04X", id);
  return buf;
}

std::string access_text(const can::ParamDef& p) {
  if (p.access == can::Access::read_only) return "ro";
  std::string out = "rw/";
  out += can::to_string(p.apply);
  if (can::safety_param(p)) out += "/safety";
  return out;
}

nlohmann::json value_json(const can::ParamDef& p, double v) {
  if (p.values[0] != '\0') return format_param_value(p, v);
  if (p.type == can::ParamType::f32) return v;
  return static_cast<long long>(v);
}

nlohmann::json param_json(const can::ParamDef& p, double v) {
  return {{"id", p.id},
          {"name", p.name},
          {"value", value_json(p, v)},
          {"unit", p.unit},
          {"range", can_host::range_text(p)},
          {"access", p.access == can::Access::read_only ? "ro" : "rw"},
          {"safety", can::safety_param(p)},
          {"apply", can::to_string(p.apply)},
          {"doc", p.doc}};
}

std::string with_unit(const can::ParamDef& p, double v) {
  std::string out = format_param_value(p, v);
  if (p.unit[0] != '\0' && p.values[0] == '\0') out.append(" ").append(p.unit);
  return out;
}

struct ListOptions {
  std::string filter;
};

int run_list(const ListOptions& o, Session& session, Report& report) {
  can_host::NodeClient& client = session.client();
  char line[256];
  std::snprintf(line, sizeof line, "%-6s  %-34s  %14s  %-7s  %-26s  %s", "id", "name", "value", "unit", "range",
                "access");
  report.line(line);
  nlohmann::json list = nlohmann::json::array();
  for (const can::ParamDef& p : can::param_table()) {
    if (!o.filter.empty() && std::string(p.name).find(o.filter) == std::string::npos) continue;
    const double v = client.get(p);
    std::snprintf(line, sizeof line, "%-6s  %-34s  %14s  %-7s  %-26s  %s", id_text(p.id).c_str(), p.name,
                  format_param_value(p, v).c_str(), p.unit, can_host::range_text(p).c_str(), access_text(p).c_str());
    report.line(line);
    list.push_back(param_json(p, v));
  }
  report.data["params"] = list;
  return kExitOk;
}

// Every parameter the arguments name (globs and dotted prefixes expand),
// each once, in the order given; all checked before anything is sent.
std::vector<const can::ParamDef*> params_named(const std::vector<std::string>& names) {
  std::vector<const can::ParamDef*> params;
  std::set<std::uint16_t> seen;
  for (const std::string& n : names) {
    std::vector<const can::ParamDef*> matched = can_host::params_matching(n);
    if (matched.empty()) {
      if (n.find_first_of("*?[") != std::string::npos) {
        std::string message = "no parameter matches '";
        throw BadInput(message.append(n).append("'; `tnvctl params list` shows them all"));
      }
      param_named(n);  // throws, with "did you mean"
    }
    for (const can::ParamDef* p : matched)
      if (seen.insert(p->id).second) params.push_back(p);
  }
  return params;
}

int run_get(const std::vector<std::string>& names, Session& session, Report& report) {
  const std::vector<const can::ParamDef*> params = params_named(names);
  can_host::NodeClient& client = session.client();
  nlohmann::json list = nlohmann::json::array();
  for (const can::ParamDef* p : params) {
    const double v = client.get(*p);
    std::string text = p->name;
    report.line(text.append(" = ").append(with_unit(*p, v)));
    list.push_back(param_json(*p, v));
  }
  report.data["params"] = list;
  return kExitOk;
}

// A safety parameter's value outside its range still goes to the node,
// which answers commissioning_required outside commissioning mode before
// it checks the range (and out_of_range in it): the refusal that matters
// comes first. Only a number the wire carries exactly is sent.
std::optional<double> safety_value_for_the_node(const can::ParamDef& p, const std::string& text) {
  char* end = nullptr;
  const double number = std::strtod(text.c_str(), &end);
  if (text.empty() || end == nullptr || *end != '\0') return std::nullopt;
  const std::optional<double> v = number;
  if (can::check_value(p, *v) != can::ErrorCode::out_of_range) return std::nullopt;
  if (p.type != can::ParamType::f32 && can::from_wire(p, can::to_wire(p, *v)) != *v) return std::nullopt;
  if (p.type == can::ParamType::f32 && !std::isfinite(static_cast<float>(*v))) return std::nullopt;
  return v;
}

using Change = can_host::ParamAssignment;

std::vector<Change> parse_assignments(const std::vector<std::string>& assignments) {
  std::vector<Change> changes;
  std::set<std::uint16_t> seen;
  for (const std::string& a : assignments) {
    const auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0) {
      std::string message = "'";
      message.append(a).append("': expected NAME=VALUE");
      throw BadInput(message);
    }
    const can::ParamDef& p = param_named(a.substr(0, eq));
    std::string error;
    std::optional<double> v = can_host::parse_param_value(p, a.substr(eq + 1), error);
    if (!v && can::safety_param(p)) v = safety_value_for_the_node(p, a.substr(eq + 1));
    if (!v) throw BadInput(error);
    if (!seen.insert(p.id).second) {
      std::string message = p.name;
      message += " is given twice";
      throw BadInput(message);
    }
    changes.push_back({&p, *v});
  }
  return changes;
}

std::size_t unique_ids(const std::vector<Change>& changes) {
  std::set<std::uint16_t> ids;
  for (const Change& c : changes) ids.insert(c.param->id);
  return ids.size();
}

}  // namespace

int set_params(const std::vector<std::string>& assignments, Session& session, Report& report) {
  const std::vector<Change> changes = parse_assignments(assignments);
  can_host::NodeClient& client = session.client();
  std::vector<double> before;
  for (const Change& c : changes) before.push_back(client.get(*c.param));
  const std::vector<double> staged = can_host::stage_params(client, changes);
  std::vector<double> after;
  try {
    after = can_host::commit_params(client, changes, staged);
  } catch (const can_host::ParamSetMismatch& e) {
    throw RunFailed(e.what());
  }
  const std::uint16_t applied = static_cast<std::uint16_t>(unique_ids(changes));
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t i = 0; i < changes.size(); ++i) {
    const can::ParamDef& p = *changes[i].param;
    const double now = after[i];
    std::string text = p.name;
    text.append(" = ").append(with_unit(p, now)).append(" (was ").append(format_param_value(p, before[i])).append(")");
    report.line(text);
    nlohmann::json j = param_json(p, now);
    j["was"] = value_json(p, before[i]);
    list.push_back(j);
  }
  report.data["applied"] = applied;
  report.data["params"] = list;
  return kExitOk;
}

namespace {

int run_storage_command(can::CommandCode code, Session& session, Report& report) {
  can_host::NodeClient& client = session.client();
  try {
    client.command(code);
  } catch (const RequestError& e) {
    if (e.kind() != RequestError::Kind::refused || e.code() != can::ErrorCode::commissioning_required) throw;
    std::string message = e.what();
    message.append(": the stored set changes safety parameters: ").append(can_host::kEnterCommissioning);
    throw RequestError(RequestError::Kind::refused, message, e.code());
  }
  std::string text;
  switch (code) {
    case can::CommandCode::save_params: text = "parameters saved"; break;
    case can::CommandCode::load_params: text = "stored parameters loaded"; break;
    default: text = "defaults restored (not saved until `params save`)"; break;
  }
  if (const can_host::EmulatedBus* emu = session.emulated(); emu != nullptr && code != can::CommandCode::restore_defaults) {
    text.append(" (").append(emu->storage_path()).append(")");
    report.data["storage"] = emu->storage_path();
  }
  report.line(text);
  return kExitOk;
}

}  // namespace

void add_params_commands(CLI::App& app, ActionSlot& slot) {
  CLI::App* params = app.add_subcommand("params", "read, change, save and load the node's parameters");
  params->require_subcommand(1);

  auto list = std::make_shared<ListOptions>();
  CLI::App* list_cmd = params->add_subcommand("list", "every parameter: id, name, value, unit, range, access/apply");
  list_cmd->add_option("--filter", list->filter, "only names containing this text (e.g. x.sliding)");
  list_cmd->callback([&slot, list] {
    slot = Action{"params list", true, [list](Session& s, Report& r) { return run_list(*list, s, r); }};
  });

  auto names = std::make_shared<std::vector<std::string>>();
  CLI::App* get_cmd = params->add_subcommand("get", "read parameters by name or id");
  get_cmd->add_option("names", *names,
                      "NAME, id (0x0116), glob ('x.*.gamma', quoted) or group prefix (x.sliding) ...")
      ->required();
  get_cmd->callback([&slot, names] {
    slot = Action{"params get", true, [names](Session& s, Report& r) { return run_get(*names, s, r); },
                  [names] { params_named(*names); }};
  });

  auto assignments = std::make_shared<std::vector<std::string>>();
  CLI::App* set_cmd = params->add_subcommand(
      "set", "change parameters: NAME=VALUE ...; staged and committed as one set (all or nothing)");
  set_cmd->add_option("assignments", *assignments, "NAME=VALUE ... (enums by name: x.controller=pid)")->required();
  set_cmd->callback([&slot, assignments] {
    slot = Action{"params set", true, [assignments](Session& s, Report& r) { return set_params(*assignments, s, r); },
                  [assignments] { parse_assignments(*assignments); }};
  });

  params->add_subcommand("save", "write the live parameters to the node's storage")->callback([&slot] {
    slot = Action{"params save", true,
                  [](Session& s, Report& r) { return run_storage_command(can::CommandCode::save_params, s, r); }};
  });
  params->add_subcommand("load", "apply the stored parameters (all or nothing; at rest only)")->callback([&slot] {
    slot = Action{"params load", true,
                  [](Session& s, Report& r) { return run_storage_command(can::CommandCode::load_params, s, r); }};
  });
  params->add_subcommand("defaults", "restore the papers' defaults (not saved; at rest only)")->callback([&slot] {
    slot = Action{"params defaults", true, [](Session& s, Report& r) {
                    return run_storage_command(can::CommandCode::restore_defaults, s, r);
                  }};
  });
  add_param_file_commands(*params, slot);
}

}  // namespace tnv::tnvctl
