#include "tools/campaign/campaign_file.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <toml++/toml.h>

#include "emulator/scenario_file.hpp"
#include "emulator/text_file.hpp"
#include "firmware/can/param_table.hpp"
#include "tools/campaign/experiment.hpp"
#include "tools/gcode/gcode_program.hpp"
#include "tools/campaign/run_inputs.hpp"
#include "tools/can/param_text.hpp"

namespace tnv::campaign {

const char* to_string(DistributionKind kind) noexcept {
  switch (kind) {
    case DistributionKind::uniform: return "uniform";
    case DistributionKind::normal: return "normal";
    case DistributionKind::lognormal: return "lognormal";
    case DistributionKind::list: return "list";
  }
  return "?";
}

nlohmann::ordered_json value_at(const VaryInput& input, double u) {
  switch (input.kind) {
    case DistributionKind::uniform: return input.a + (input.b - input.a) * u;
    case DistributionKind::normal: return input.a + input.b * inverse_normal_cdf(u);
    case DistributionKind::lognormal: return input.a * std::exp(input.b * inverse_normal_cdf(u));
    case DistributionKind::list: {
      const std::size_t n = input.values.size();
      const auto k = std::min(n - 1, static_cast<std::size_t>(u * static_cast<double>(n)));
      return input.values[k];
    }
  }
  return nullptr;
}

namespace {

class CampaignReader {
 public:
  CampaignReader(std::string_view source, std::filesystem::path base_dir)
      : source_(source), base_dir_(std::move(base_dir)) {}

  CampaignResult read(std::string_view text) {
    toml::table root;
    try {
      root = toml::parse(text, source_);
    } catch (const toml::parse_error& e) {
      return fail_at(e.source().begin, "", "TOML syntax error: " + emu::one_line(e.description()));
    }
    CampaignSpec spec;
    spec.source = source_;
    const toml::node* vary = nullptr;
    toml::source_position vary_at{};
    const Experiment* experiment = nullptr;
    const toml::node* controllers = nullptr;
    toml::source_position controllers_at{};
    std::vector<OwnKey> own_keys;
    bool has[5] = {};
    for (auto&& [key, node] : root) {
      const std::string name(key.str());
      const toml::source_position at = key.source().begin;
      if (name == "experiment") {
        has[0] = true;
        if (!read_string(at, name, node, spec.experiment)) return error();
        experiment = find_experiment(spec.experiment);
        if (experiment == nullptr)
          return fail_at(at, name, "\"" + spec.experiment + "\": campaigns run " + experiment_names());
      } else if (name == "controllers") {
        has[1] = true;
        controllers = &node;
        controllers_at = at;
      } else if (name == "scenario") {
        has[2] = true;
        if (!read_string(at, name, node, spec.scenario) || !resolve_scenario(at, spec)) return error();
      } else if (name == "runs") {
        has[3] = true;
        const auto* i = node.as_integer();
        if (i == nullptr || i->get() < 1 || i->get() > static_cast<std::int64_t>(kMaxCampaignRuns))
          return fail_at(at, name, "must be an integer in 1.." + std::to_string(kMaxCampaignRuns));
        spec.runs = static_cast<std::size_t>(i->get());
      } else if (name == "seed") {
        has[4] = true;
        const auto* i = node.as_integer();
        if (i == nullptr || i->get() < 0) return fail_at(at, name, "must be an integer >= 0");
        spec.seed = static_cast<std::uint64_t>(i->get());
      } else if (name == "sampling") {
        std::string s;
        if (!read_string(at, name, node, s)) return error();
        if (s == "random") {
          spec.sampling = Sampling::random;
        } else if (s == "latin-hypercube") {
          spec.sampling = Sampling::latin_hypercube;
        } else {
          return fail_at(at, name, "\"" + s + "\": must be \"random\" or \"latin-hypercube\"");
        }
      } else if (name == "limit_um") {
        const auto v = node.value<double>();
        if (!v || !(*v > 0.0) || !std::isfinite(*v)) return fail_at(at, name, "must be a number > 0");
        spec.limit_um = *v;
      } else if (name == "vary") {
        vary = &node;
        vary_at = at;
      } else {
        own_keys.push_back({name, &node, at});  // the experiment's own, once it is known
      }
    }
    static constexpr const char* kRequired[] = {"experiment", "controllers", "scenario", "runs", "seed"};
    if (!has[0]) return fail_at(toml::source_position{1, 1}, "experiment", "required");
    if (!read_settings(own_keys, *experiment, spec)) return error();
    has[1] = has[1] || experiment->controllers != ControllerUse::choose;
    for (std::size_t k = 1; k < 5; ++k)
      if (!has[k]) return fail_at(toml::source_position{1, 1}, kRequired[k], "required");
    if (!read_controller_choice(controllers, controllers_at, *experiment, spec.controllers)) return error();
    if (vary != nullptr && !read_vary(vary_at, *vary, spec)) return error();
    return {std::move(spec), {}};
  }

 private:
  struct OwnKey {
    std::string name;
    const toml::node* node;
    toml::source_position at;
  };

  bool read_controller_choice(const toml::node* node, const toml::source_position& at, const Experiment& experiment,
                              std::vector<fw::ControllerKind>& out) {
    switch (experiment.controllers) {
      case ControllerUse::choose: return read_controllers(at, *node, out);
      case ControllerUse::rdvsc_only:
        if (node != nullptr) {
          if (!read_controllers(at, *node, out)) return false;
          if (out.size() != 1 || out[0] != fw::ControllerKind::rdvsc)
            return fail(at, "controllers", "\"" + experiment.name + "\" runs R-DVSC+DDC only: [\"rdvsc\"] or leave it out");
        }
        out = {fw::ControllerKind::rdvsc};
        return true;
      case ControllerUse::none:
        if (node != nullptr)
          return fail(at, "controllers", "\"" + experiment.name + "\" runs no axis loops: leave it out");
        return true;
    }
    return true;
  }

  // The experiment's own keys: typed, required ones present, defaults
  // filled in, then checked as a whole by the experiment.
  bool read_settings(const std::vector<OwnKey>& keys, const Experiment& experiment, CampaignSpec& spec) {
    std::map<std::string, toml::source_position> where;
    for (const OwnKey& k : keys) {
      const SettingKey* def = nullptr;
      for (const SettingKey& s : experiment.settings)
        if (s.name == k.name) def = &s;
      if (def == nullptr) {
        for (const Experiment* other : all_experiments())
          for (const SettingKey& s : other->settings)
            if (s.name == k.name)
              return fail(k.at, k.name, "a key of experiment \"" + other->name + "\", not of \"" + experiment.name + "\"");
        return fail(k.at, k.name, k.node->is_table() ? "unknown section" : "unknown key");
      }
      nlohmann::ordered_json value;
      if (!read_setting(k, *def, value)) return false;
      spec.settings[k.name] = value;
      where[k.name] = k.at;
    }
    nlohmann::ordered_json ordered = nlohmann::ordered_json::object();  // the experiment's order
    for (const SettingKey& s : experiment.settings) {
      if (spec.settings.contains(s.name)) {
        ordered[s.name] = spec.settings[s.name];
      } else if (s.required) {
        return fail(toml::source_position{1, 1}, s.name, "required for experiment \"" + experiment.name + "\"");
      } else {
        ordered[s.name] = s.default_value;
      }
    }
    spec.settings = std::move(ordered);
    const auto at = [&](const std::string& key) {
      const auto it = where.find(key);
      return it != where.end() ? it->second : toml::source_position{1, 1};
    };
    if (spec.settings.contains("program")) {
      const std::filesystem::path path = base_dir_ / spec.settings["program"].get<std::string>();
      std::string error;
      if (!gcode::read_program_file(path.string(), spec.program_text, error)) return fail(at("program"), "program", error);
    }
    std::string key;
    const std::string why = experiment.check_settings(spec.settings, spec.program_text, key);
    if (!why.empty()) return fail(at(key), key, why);
    return true;
  }

  bool read_setting(const OwnKey& k, const SettingKey& def, nlohmann::ordered_json& value) {
    switch (def.type) {
      case SettingType::string:
        if (const auto* s = k.node->as_string()) {
          value = s->get();
          return true;
        }
        return fail(k.at, k.name, "expected a string");
      case SettingType::number:
        if (const auto v = k.node->value<double>(); v && std::isfinite(*v) && (k.node->is_number())) {
          value = *v;
          return true;
        }
        return fail(k.at, k.name, "expected a finite number");
      case SettingType::integer:
        if (const auto* i = k.node->as_integer()) {
          value = i->get();
          return true;
        }
        return fail(k.at, k.name, "expected an integer");
      case SettingType::boolean:
        if (const auto* b = k.node->as_boolean()) {
          value = b->get();
          return true;
        }
        return fail(k.at, k.name, "expected true or false");
      case SettingType::integer_list:
        if (const auto* list = k.node->as_array()) {
          value = nlohmann::ordered_json::array();
          for (const toml::node& item : *list) {
            const auto* i = item.as_integer();
            if (i == nullptr) return fail(k.at, k.name, "expected a list of integers");
            value.push_back(i->get());
          }
          return true;
        }
        return fail(k.at, k.name, "expected a list of integers");
    }
    return fail(k.at, k.name, "unsupported");
  }

  bool read_string(const toml::source_position& at, const std::string& key, const toml::node& node, std::string& out) {
    const auto* s = node.as_string();
    if (s == nullptr) return fail(at, key, "expected a string");
    out = s->get();
    return true;
  }

  bool read_controllers(const toml::source_position& at, const toml::node& node,
                        std::vector<fw::ControllerKind>& out) {
    const auto* list = node.as_array();
    if (list == nullptr || list->empty()) return fail(at, "controllers", "expected a non-empty list, e.g. [\"pid\", \"rdvsc\"]");
    for (const toml::node& item : *list) {
      const auto* s = item.as_string();
      std::optional<fw::ControllerKind> kind;
      for (const fw::ControllerKind k : {fw::ControllerKind::pid, fw::ControllerKind::dvsc, fw::ControllerKind::rdvsc})
        if (s != nullptr && s->get() == fw::to_string(k)) kind = k;
      if (!kind) return fail(item.source().begin, "controllers", "each must be \"pid\", \"dvsc\" or \"rdvsc\"");
      for (const fw::ControllerKind k : out)
        if (k == *kind) return fail(item.source().begin, "controllers", std::string("\"") + fw::to_string(k) + "\" twice");
      out.push_back(*kind);
    }
    return true;
  }

  bool resolve_scenario(const toml::source_position& at, CampaignSpec& spec) {
    if (auto builtin = emu::builtin_scenario(spec.scenario)) {
      spec.base = *builtin;
      return true;
    }
    const std::filesystem::path path = base_dir_ / spec.scenario;
    std::string text, error;
    if (!emu::read_text_file(path.string(), emu::kMaxScenarioBytes, text, error)) {
      std::string names;
      for (const std::string& n : emu::builtin_scenario_names()) names += (names.empty() ? "" : ", ") + n;
      return fail(at, "scenario", "\"" + spec.scenario + "\" is neither a built-in (" + names + ") nor a readable file (" +
                                      emu::one_line(error) + ")");
    }
    emu::ScenarioResult r = emu::parse_scenario_text(text, path.string());
    if (!r.scenario) return fail(at, "scenario", r.error);
    spec.base = *r.scenario;
    spec.scenario_text = std::move(text);
    return true;
  }

  bool read_pair(const toml::source_position& at, const std::string& key, const toml::node& node, double& a,
                 double& b) {
    const auto* list = node.as_array();
    if (list == nullptr || list->size() != 2) return fail(at, key, "expected two numbers [a, b]");
    const auto x = list->get(0)->value<double>();
    const auto y = list->get(1)->value<double>();
    if (!x || !y || !std::isfinite(*x) || !std::isfinite(*y)) return fail(at, key, "expected two finite numbers [a, b]");
    a = *x;
    b = *y;
    return true;
  }

  bool read_vary(const toml::source_position& at, const toml::node& node, CampaignSpec& spec) {
    const auto* table = node.as_table();
    if (table == nullptr) return fail(at, "vary", "expected a table");
    for (auto&& [key, entry] : *table) {
      VaryInput v;
      v.name = std::string(key.str());
      v.line = static_cast<int>(key.source().begin.line);
      v.column = static_cast<int>(key.source().begin.column);
      const toml::source_position where = key.source().begin;
      const std::string path = "vary.\"" + v.name + "\"";
      const auto* d = entry.as_table();
      if (d == nullptr || d->size() != 1)
        return fail(where, path, "expected one distribution: { uniform = [lo, hi] }, { normal = [mean, sigma] }, "
                                 "{ lognormal = [median, sigma] } or { list = [...] }");
      const auto only = d->begin();
      const std::string dname(only->first.str());
      const toml::node& dnode = only->second;
      if (dname == "uniform") {
        v.kind = DistributionKind::uniform;
        if (!read_pair(where, path, dnode, v.a, v.b)) return false;
        if (!(v.a < v.b)) return fail(where, path, "uniform [lo, hi] needs lo < hi");
      } else if (dname == "normal" || dname == "lognormal") {
        v.kind = dname == "normal" ? DistributionKind::normal : DistributionKind::lognormal;
        if (!read_pair(where, path, dnode, v.a, v.b)) return false;
        if (!(v.b > 0.0)) return fail(where, path, dname + " [" + (dname == "normal" ? "mean" : "median") + ", sigma] needs sigma > 0");
        if (v.kind == DistributionKind::lognormal && !(v.a > 0.0)) return fail(where, path, "lognormal [median, sigma] needs median > 0");
      } else if (dname == "list") {
        v.kind = DistributionKind::list;
        const auto* list = dnode.as_array();
        if (list == nullptr || list->empty()) return fail(where, path, "list needs at least one value");
        for (const toml::node& item : *list) {
          if (const auto* i = item.as_integer()) {
            v.values.push_back(i->get());
          } else if (const auto* f = item.as_floating_point()) {
            if (!std::isfinite(f->get())) return fail(where, path, "list values must be finite");
            v.values.push_back(f->get());
          } else if (const auto* b = item.as_boolean()) {
            v.values.push_back(b->get());
          } else if (const auto* s = item.as_string()) {
            v.values.push_back(s->get());
          } else {
            return fail(where, path, "list values must be numbers, booleans or strings");
          }
        }
      } else {
        return fail(where, path, "\"" + dname + "\": not a distribution (uniform, normal, lognormal, list)");
      }
      for (const VaryInput& other : spec.vary)
        if (other.name == v.name) return fail(where, path, "varied twice");
      if (!classify_and_check(where, path, spec, v)) return false;
      spec.vary.push_back(std::move(v));
    }
    // toml++ keeps a table's keys sorted; the file's order is the user's.
    std::stable_sort(spec.vary.begin(), spec.vary.end(), [](const VaryInput& x, const VaryInput& y) {
      return x.line != y.line ? x.line < y.line : x.column < y.column;
    });
    return true;
  }

  // A firmware parameter by its exact name, else a scenario key; the
  // distribution's end points (uniform), centre (normal, lognormal) or
  // every value (list) must be valid for it. Every drawn value is checked
  // again when the campaign is planned.
  bool classify_and_check(const toml::source_position& at, const std::string& path, const CampaignSpec& spec,
                          VaryInput& v) {
    const fw::can::ParamDef* p = can_host::find_param_by_text(v.name);
    v.is_parameter = p != nullptr && v.name == p->name;
    std::vector<std::pair<std::string, nlohmann::ordered_json>> probes;
    switch (v.kind) {
      case DistributionKind::uniform:
        probes = {{"low end", v.a}, {"high end", v.b}};
        break;
      case DistributionKind::normal: probes = {{"mean", v.a}}; break;
      case DistributionKind::lognormal: probes = {{"median", v.a}}; break;
      case DistributionKind::list:
        for (const auto& value : v.values) probes.emplace_back("value " + value.dump(), value);
        break;
    }
    for (const auto& [what, value] : probes) {
      nlohmann::ordered_json values = nlohmann::ordered_json::object();
      values[v.name] = value;
      const RunSetup setup = resolve_run_inputs(spec.base, {{v.name, v.is_parameter}}, values, spec.experiment);
      if (setup.unknown_key) {
        const std::string near = can_host::closest_param_name(v.name);
        return fail(at, path, "neither a scenario key (docs/scenarios.md) nor a firmware parameter (tnvctl params list)" +
                                  (near.empty() ? std::string() : "; did you mean " + near + "?"));
      }
      if (const std::string why = find_experiment(spec.experiment)->check_input(v.name, v.is_parameter); !why.empty())
        return fail(at, path, "not an input of experiment \"" + spec.experiment + "\": " + why);
      if (setup.scenario) continue;
      return fail(at, path, std::string(to_string(v.kind)) + " " + what + " (" + param_value_text(value) +
                                ") is outside the key's valid range: " + setup.error);
    }
    return true;
  }

  bool fail(const toml::source_position& at, const std::string& key, const std::string& message) {
    error_ = source_ + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) + ": " +
             (key.empty() ? "" : key + ": ") + emu::one_line(message);
    return false;
  }
  CampaignResult fail_at(const toml::source_position& at, const std::string& key, const std::string& message) {
    fail(at, key, message);
    return error();
  }
  CampaignResult error() const { return {std::nullopt, error_}; }

  std::string source_;
  std::filesystem::path base_dir_;
  std::string error_;
};

}  // namespace

CampaignResult parse_campaign_text(std::string_view text, std::string_view source_name,
                                   const std::filesystem::path& base_dir) {
  return CampaignReader(source_name, base_dir).read(text);
}

CampaignResult load_campaign_file(const std::string& path) {
  constexpr std::size_t kMaxCampaignBytes = std::size_t{1} << 20;
  std::string text, error;
  if (!emu::read_text_file(path, kMaxCampaignBytes, text, error)) return {std::nullopt, emu::one_line(error)};
  return parse_campaign_text(text, path, std::filesystem::path(path).parent_path());
}

}  // namespace tnv::campaign
