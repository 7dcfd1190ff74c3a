#include "emulator/scenario_file.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <variant>
#include <vector>

#include <toml++/toml.h>

#include "emulator/scenario_keys.hpp"
#include "emulator/scenario_validation.hpp"
#include "emulator/text_file.hpp"
#include "emulator/toml_type_name.hpp"
#include "hal/axis_choice.hpp"

namespace tnv::emu {

namespace {

// Walks the parsed document into a Scenario, remembering where each key was.
class ScenarioReader {
 public:
  explicit ScenarioReader(std::string_view source_name) : source_(source_name) {}

  // The sections and keys of the table (scenario_keys.hpp), [[fault]] beside them.
  bool read(const toml::table& root, Scenario& s) { return read_table(root, "", s); }

  bool check(const Scenario& s) {
    const auto violation = find_scenario_violation(s, [this](std::string_view k) { return given(k); });
    if (!violation) return true;
    const auto where = positions_.find(violation->key);
    if (where == positions_.end()) {
      error_ = std::string(source_) + ": " + violation->key + ": " + violation->message;
    } else {
      error_ = location(where->second) + violation->key + ": " + violation->message;
    }
    return false;
  }

  bool unknown_key() const { return unknown_key_; }
  bool given(std::string_view key) const { return positions_.find(std::string(key)) != positions_.end(); }
  const std::string& error() const { return error_; }

 private:
  bool read_table(const toml::table& table, const std::string& section, Scenario& s) {
    for (auto&& entry : table) {  // not a structured binding: clang 14 cannot capture one in a lambda
      const toml::key& key = entry.first;
      const toml::node& node = entry.second;
      const std::string_view name = key.str();
      const std::string path = section.empty() ? std::string(name) : section + "." + std::string(name);
      if (section.empty() && name == "fault") {
        if (!read_faults(key, node, s)) return false;
      } else if (section == "stock" && name == "hole") {
        if (!read_holes(key, node, s)) return false;
      } else if (const ScenarioKey* row = find_scenario_key(section, name)) {
        const bool ok = std::visit([&](auto* target) { return assign(key, path, node, target); }, row->target(s));
        if (!ok) return false;
      } else if (is_scenario_section(path)) {
        const toml::table* inner = node.as_table();
        if (inner == nullptr) return fail(key, path, std::string("expected a table, got ") + toml_type_name(node));
        if (!read_table(*inner, path, s)) return false;
      } else {
        return unknown(key, path, node);
      }
    }
    return true;
  }

  // [[fault]] tables: kind first (it decides which keys apply), then the rest.
  bool read_faults(const toml::key& key, const toml::node& node, Scenario& s) {
    const toml::array* list = node.as_array();
    if (list == nullptr || !list->is_array_of_tables()) {
      return fail(key, "fault", std::string("expected an array of tables ([[fault]]), got ") + toml_type_name(node));
    }
    for (std::size_t i = 0; i < list->size(); ++i) {
      const toml::table& table = *list->get(i)->as_table();
      const std::string path = "fault[" + std::to_string(i) + "]";
      FaultSpec f;
      if (!read_fault_kind(table, path, f)) return false;
      const FaultKeys keys = fault_keys(f.kind);
      bool has_start = false, has_axis = false, has_side = false, has_code = false, has_delay = false,
           has_counts = false;
      for (auto&& entry : table) {  // not a structured binding: clang 14 cannot capture one in a lambda
        const toml::key& field_key = entry.first;
        const toml::node& field_node = entry.second;
        const std::string_view name = field_key.str();
        const std::string field_path = path + "." + std::string(name);
        const auto not_for_kind = [&] {
          return fail(field_key, field_path, std::string("not a key of kind ") + to_string(f.kind));
        };
        bool ok = true;
        if (name == "kind") {
          continue;
        } else if (name == "start_s") {
          ok = assign(field_key, field_path, field_node, &f.start_s);
          has_start = true;
        } else if (name == "duration_s") {
          ok = keys.duration ? assign(field_key, field_path, field_node, &f.duration_s) : not_for_kind();
        } else if (name == "axis") {
          ok = keys.axis ? read_axis(field_key, field_path, field_node, f.axis) : not_for_kind();
          has_axis = true;
        } else if (name == "side") {
          ok = keys.side ? read_choice(field_key, field_path, field_node, "+", "-", f.positive_side, true, false)
                         : not_for_kind();
          has_side = true;
        } else if (name == "code") {
          ok = keys.code ? assign(field_key, field_path, field_node, &f.dac_code) : not_for_kind();
          has_code = true;
        } else if (name == "ticks") {
          ok = keys.ticks ? assign(field_key, field_path, field_node, &f.ticks) : not_for_kind();
        } else if (name == "delay_us") {
          ok = keys.delay ? assign(field_key, field_path, field_node, &f.delay_us) : not_for_kind();
          has_delay = true;
        } else if (name == "counts") {
          ok = keys.counts ? assign(field_key, field_path, field_node, &f.counts) : not_for_kind();
          has_counts = true;
        } else {
          ok = unknown(field_key, field_path, field_node);
        }
        if (!ok) return false;
      }
      const auto missing = [&](const char* leaf) {
        error_ = location(table.source().begin) + path + "." + leaf + ": required for kind " + to_string(f.kind);
        return false;
      };
      if (!has_start) return missing("start_s");
      if (keys.axis && !has_axis) return missing("axis");
      if (keys.side && !has_side) return missing("side");
      if (keys.code && !has_code) return missing("code");
      if (keys.delay && !has_delay) return missing("delay_us");
      if (keys.counts && !has_counts) return missing("counts");
      s.faults.push_back(f);
    }
    return true;
  }

  // [[stock.hole]] tables: x_mm, y_mm, diameter_mm, and depth_mm or through = true.
  bool read_holes(const toml::key& key, const toml::node& node, Scenario& s) {
    constexpr double kRangeMm = 1000.0;  // machine coordinates, as the stock's rectangle
    const toml::array* list = node.as_array();
    if (list == nullptr || !list->is_array_of_tables()) {
      return fail(key, "stock.hole",
                  std::string("expected an array of tables ([[stock.hole]]), got ") + toml_type_name(node));
    }
    if (list->size() > kMaxStockHoles) {
      return fail(key, "stock.hole", "at most " + std::to_string(kMaxStockHoles) + " holes (got " +
                                         std::to_string(list->size()) + ")");
    }
    std::vector<StockHole> holes;
    for (std::size_t i = 0; i < list->size(); ++i) {
      const toml::table& table = *list->get(i)->as_table();
      const std::string path = "stock.hole[" + std::to_string(i) + "]";
      StockHole h;
      bool has_x = false, has_y = false, has_diameter = false, has_depth = false, through = false;
      for (auto&& entry : table) {  // not a structured binding: clang 14 cannot capture one in a lambda
        const toml::key& field_key = entry.first;
        const toml::node& field_node = entry.second;
        const std::string_view name = field_key.str();
        const std::string field_path = path + "." + std::string(name);
        const auto within = [&](double value, double lo, double hi, const char* what) {
          if (std::isfinite(value) && value > lo && value <= hi) return true;
          char text[96];
          std::snprintf(text, sizeof text, "must be in (%g, %g] (%s)", lo, hi, what);
          return fail(field_key, field_path, text);
        };
        bool ok = true;
        if (name == "x_mm") {
          ok = assign(field_key, field_path, field_node, &h.x_mm) && within(h.x_mm, -kRangeMm, kRangeMm, "machine coordinates");
          has_x = true;
        } else if (name == "y_mm") {
          ok = assign(field_key, field_path, field_node, &h.y_mm) && within(h.y_mm, -kRangeMm, kRangeMm, "machine coordinates");
          has_y = true;
        } else if (name == "diameter_mm") {
          ok = assign(field_key, field_path, field_node, &h.diameter_mm) &&
               within(h.diameter_mm, 0.0, 500.0, "a hole's diameter");
          has_diameter = true;
        } else if (name == "depth_mm") {
          ok = assign(field_key, field_path, field_node, &h.depth_mm) &&
               within(h.depth_mm, 0.0, 2.0 * kRangeMm, "a depth below the stock top");
          has_depth = true;
        } else if (name == "through") {
          ok = assign(field_key, field_path, field_node, &through);
          if (ok && !through) ok = fail(field_key, field_path, "only through = true is meaningful (else give depth_mm)");
        } else {
          ok = unknown(field_key, field_path, field_node);
        }
        if (!ok) return false;
      }
      const auto missing = [&](const std::string& leaf, const char* why) {
        error_ = location(table.source().begin) + path + "." + leaf + ": " + why;
        return false;
      };
      if (!has_x) return missing("x_mm", "required");
      if (!has_y) return missing("y_mm", "required");
      if (!has_diameter) return missing("diameter_mm", "required");
      if (has_depth == through) return missing(has_depth ? "through" : "depth_mm", "give depth_mm or through = true, one of them");
      holes.push_back(h);  // through: depth_mm stays infinite
    }
    s.stock.holes = std::move(holes);
    return true;
  }

  bool read_fault_kind(const toml::table& table, const std::string& path, FaultSpec& f) {
    std::string kinds;
    for (FaultKind kind : kFaultKinds) kinds.append(kinds.empty() ? "" : ", ").append(to_string(kind));
    for (auto&& [field_key, field_node] : table) {
      if (field_key.str() != "kind") continue;
      std::string name;
      if (!assign(field_key, path + ".kind", field_node, &name)) return false;
      const auto kind = fault_kind_from_string(name);
      if (!kind) return fail(field_key, path + ".kind", "unknown kind \"" + name + "\" (one of: " + kinds + ")");
      f.kind = *kind;
      return true;
    }
    error_ = location(table.source().begin) + path + ".kind: required (one of: " + kinds + ")";
    return false;
  }

  // A string that must be one of two spellings.
  template <typename T>
  bool read_choice(const toml::key& key, const std::string& path, const toml::node& node, const char* first,
                   const char* second, T& target, T first_value, T second_value) {
    std::string text;
    if (!assign(key, path, node, &text)) return false;
    if (text == first) {
      target = first_value;
    } else if (text == second) {
      target = second_value;
    } else {
      return fail(key, path, std::string("must be \"") + first + "\" or \"" + second + "\" (got \"" + text + "\")");
    }
    return true;
  }

  bool read_axis(const toml::key& key, const std::string& path, const toml::node& node, hal::Axis& target) {
    std::string text;
    if (!assign(key, path, node, &text)) return false;
    const std::optional<hal::Axis> axis = hal::axis_from_name(text);
    if (!axis) return fail(key, path, "must be " + std::string(hal::kQuotedAxisChoices) + " (got \"" + text + "\")");
    target = *axis;
    return true;
  }

  bool assign(const toml::key& key, const std::string& path, const toml::node& node, double* target) {
    if (const auto* f = node.as_floating_point()) {
      *target = f->get();
    } else if (const auto* i = node.as_integer()) {
      *target = static_cast<double>(i->get());
    } else {
      return fail(key, path, std::string("expected a number, got ") + toml_type_name(node));
    }
    return remember(key, path);
  }
  bool assign(const toml::key& key, const std::string& path, const toml::node& node, int* target) {
    const auto* i = node.as_integer();
    if (i == nullptr) return fail(key, path, std::string("expected an integer, got ") + toml_type_name(node));
    if (i->get() < std::numeric_limits<int>::min() || i->get() > std::numeric_limits<int>::max()) {
      return fail(key, path, "out of range (got " + std::to_string(i->get()) + ")");
    }
    *target = static_cast<int>(i->get());
    return remember(key, path);
  }
  bool assign(const toml::key& key, const std::string& path, const toml::node& node, std::uint32_t* target) {
    const auto* i = node.as_integer();
    if (i == nullptr) return fail(key, path, std::string("expected an integer, got ") + toml_type_name(node));
    if (i->get() < 0 || i->get() > std::int64_t{std::numeric_limits<std::uint32_t>::max()}) {
      return fail(key, path, "must be in 0..4294967295 (got " + std::to_string(i->get()) + ")");
    }
    *target = static_cast<std::uint32_t>(i->get());
    return remember(key, path);
  }
  bool assign(const toml::key& key, const std::string& path, const toml::node& node, bool* target) {
    const auto* b = node.as_boolean();
    if (b == nullptr) return fail(key, path, std::string("expected a boolean, got ") + toml_type_name(node));
    *target = b->get();
    return remember(key, path);
  }
  bool assign(const toml::key& key, const std::string& path, const toml::node& node, std::string* target) {
    const auto* text = node.as_string();
    if (text == nullptr) return fail(key, path, std::string("expected a string, got ") + toml_type_name(node));
    *target = text->get();
    return remember(key, path);
  }

  bool unknown(const toml::key& key, const std::string& path, const toml::node& node) {
    unknown_key_ = true;
    return fail(key, path, node.is_table() ? "unknown section" : "unknown key");
  }

  bool remember(const toml::key& key, const std::string& path) {
    positions_[path] = key.source().begin;
    return true;
  }

  bool fail(const toml::key& key, const std::string& path, const std::string& message) {
    error_ = location(key.source().begin) + path + ": " + message;
    return false;
  }

  std::string location(const toml::source_position& at) const {
    return std::string(source_) + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) + ": ";
  }

  std::string_view source_;
  std::map<std::string, toml::source_position> positions_;
  std::string error_;
  bool unknown_key_ = false;
};

}  // namespace

ScenarioResult parse_scenario_text(std::string_view text, std::string_view source_name) {
  return apply_scenario_text(Scenario{}, text, source_name);
}

ScenarioResult apply_scenario_text(const Scenario& base, std::string_view text, std::string_view source_name) {
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    const auto& at = e.source().begin;
    return {std::nullopt, std::string(source_name) + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) +
                              ": TOML syntax error: " + one_line(e.description()), false};
  }
  Scenario scenario = base;
  ScenarioReader reader(source_name);
  // one_line: a key or value quoted from the file may hold a newline (found by fuzzing).
  if (!reader.read(root, scenario) || !reader.check(scenario))
    return {std::nullopt, one_line(reader.error()), reader.unknown_key()};
  return {std::move(scenario), {}, false};
}

ScenarioResult load_scenario_file(const std::string& path) {
  std::string text, error;
  try {
    if (!read_text_file(path, kMaxScenarioBytes, text, error)) return {std::nullopt, one_line(error), false};
  } catch (const std::exception& e) {
    return {std::nullopt, path + ": cannot read file: " + one_line(e.what()), false};
  }
  return parse_scenario_text(text, path);
}

}  // namespace tnv::emu
