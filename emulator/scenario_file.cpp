#include "emulator/scenario_file.hpp"

#include <limits>
#include <map>
#include <optional>
#include <span>
#include <variant>
#include <vector>

#include <toml++/toml.h>

#include "emulator/scenario_validation.hpp"
#include "emulator/text_file.hpp"
#include "emulator/toml_type_name.hpp"
#include "hal/axis_choice.hpp"

namespace tnv::emu {

namespace {

using FieldTarget = std::variant<double*, int*, bool*, std::uint32_t*, std::string*>;
struct Field {
  std::string_view name;
  FieldTarget target;
};

// Walks the parsed document into a Scenario, remembering where each key was.
class ScenarioReader {
 public:
  explicit ScenarioReader(std::string_view source_name) : source_(source_name) {}

  bool read(const toml::table& root, Scenario& s) {
    for (auto&& [key, node] : root) {
      const std::string name(key.str());
      if (name == "name") {
        if (!assign(key, name, node, &s.name)) return false;
      } else if (name == "plant") {
        if (!read_plant(key, node, s)) return false;
      } else if (name == "cutting") {
        const Field fields[] = {{"enabled", &s.cutting.enabled},     {"spindle_rpm", &s.cutting.spindle_rpm},
                                {"flutes", &s.cutting.flutes},       {"mean_mm_s", &s.cutting.mean_mm_s},
                                {"amplitude_mm_s", &s.cutting.amplitude_mm_s}, {"exponent", &s.cutting.exponent},
                                {"phase_rad", &s.cutting.phase_rad}};
        if (!read_section(key, name, node, fields)) return false;
      } else if (name == "encoder") {
        std::vector<Field> fields{{"counts_per_rev", &s.encoder.counts_per_rev}, {"lead_mm", &s.encoder.lead_mm}};
#define TNV_ENCODER_AXIS_FIELDS(n, ...) \
  fields.push_back({"offset_counts_" #n, &s.encoder.axis_offset_counts[hal::index(hal::Axis::n)]});
        TNV_AXES(TNV_ENCODER_AXIS_FIELDS)
#undef TNV_ENCODER_AXIS_FIELDS
        if (!read_section(key, name, node, fields)) return false;
      } else if (name == "dac") {
        const Field fields[] = {{"bits", &s.dac.bits}, {"full_scale_v", &s.dac.full_scale_v},
                                {"rpm_at_full_scale", &s.dac.rpm_at_full_scale}};
        if (!read_section(key, name, node, fields)) return false;
      } else if (name == "force_sensor") {
        const Field fields[] = {{"volts_per_mm_s", &s.force_sensor.volts_per_mm_s},
                                {"volts_per_n", &s.force_sensor.volts_per_n}};
        if (!read_section(key, name, node, fields)) return false;
      } else if (name == "milling") {
        const Field fields[] = {{"enabled", &s.milling.enabled},
                                {"time_constant_s", &s.milling.time_constant_s},
                                {"force_n_per_mm_mm_s", &s.milling.force_n_per_mm_mm_s},
                                {"feed_load_mm_s_per_n", &s.milling.feed_load_mm_s_per_n},
                                {"depth_start_mm", &s.milling.depth.start_mm},
                                {"depth_peak_mm", &s.milling.depth.peak_mm},
                                {"rise_s", &s.milling.depth.rise_s},
                                {"fall_s", &s.milling.depth.fall_s}};
        if (!read_section(key, name, node, fields)) return false;
      } else if (name == "board") {
        BoardParams& b = s.board;
        std::vector<Field> fields{{"clock_start", &b.clock_start}, {"limit_switches", &b.limit_switches}};
        // Per axis: <field>_<axis>, or <field>_<axis>_<unit> where the field has a unit.
#define TNV_BOARD_AXIS_FIELDS(n, ...)                                                                      \
  {                                                                                                   \
    BoardAxisParams& a = b.axis[hal::index(hal::Axis::n)];                                            \
    fields.insert(fields.end(), {{"home_switch_" #n, &a.home_switch},                                 \
                                 {"home_" #n "_mm", &a.home_mm},                                      \
                                 {"home_" #n "_side", &a.home_side},                                  \
                                 {"index_" #n "_deg", &a.index_deg},                                  \
                                 {"limit_" #n "_min_mm", &a.limit_min_mm},                            \
                                 {"limit_" #n "_max_mm", &a.limit_max_mm},                            \
                                 {"power_up_offset_" #n "_mm", &a.power_up_offset_mm}});              \
  }
        TNV_AXES(TNV_BOARD_AXIS_FIELDS)
#undef TNV_BOARD_AXIS_FIELDS
        if (!read_section(key, name, node, fields)) return false;
      } else if (name == "noise") {
        const Field fields[] = {{"seed", &s.noise.seed},
                                {"force_adc_v_rms", &s.noise.force_adc_v_rms},
                                {"accel_g_rms", &s.noise.accel_g_rms},
                                {"accel_bias_g", &s.noise.accel_bias_g},
                                {"dac_offset_v", &s.noise.dac_offset_v},
                                {"dac_gain_error", &s.noise.dac_gain_error},
                                {"encoder_glitch_per_s", &s.noise.encoder_glitch_per_s},
                                {"encoder_glitch_counts", &s.noise.encoder_glitch_counts},
                                {"bore_gauge_um_rms", &s.noise.bore_gauge_um_rms},
                                {"bore_gauge_resolution_um", &s.noise.bore_gauge_resolution_um}};
        if (!read_section(key, name, node, fields)) return false;
      } else if (name == "io") {
        const Field fields[] = {{"read_latency_us", &s.io.read_latency_us},
                                {"write_latency_us", &s.io.write_latency_us},
                                {"jitter_us", &s.io.jitter_us}};
        if (!read_section(key, name, node, fields)) return false;
      } else if (name == "fault") {
        if (!read_faults(key, node, s)) return false;
      } else if (name == "spindle") {
        SpindleParams& sp = s.spindle;
        const Field fields[] = {{"tau_s", &sp.tau_s},
                                {"dac_bits", &sp.dac_bits},
                                {"full_scale_v", &sp.full_scale_v},
                                {"rpm_at_full_scale", &sp.rpm_at_full_scale},
                                {"accel_limit_rpm_s", &sp.accel_limit_rpm_s},
                                {"droop_rpm_per_n", &sp.droop_rpm_per_n},
                                {"encoder_counts_per_rev", &sp.encoder_counts_per_rev},
                                {"index_deg", &sp.index_deg}};
        if (!read_section(key, name, node, fields)) return false;
      } else if (name == "tool") {
        const Field fields[] = {{"diameter_mm", &s.tool.diameter_mm}, {"flutes", &s.tool.flutes},
                                {"flute_length_mm", &s.tool.flute_length_mm}, {"length_mm", &s.tool.length_mm}};
        if (!read_section(key, name, node, fields)) return false;
      } else if (name == "stock") {
        const Field fields[] = {{"top_mm", &s.stock.top_mm},     {"x_min_mm", &s.stock.x_min_mm},
                                {"x_max_mm", &s.stock.x_max_mm}, {"y_min_mm", &s.stock.y_min_mm},
                                {"y_max_mm", &s.stock.y_max_mm}};
        if (!read_section(key, name, node, fields)) return false;
      } else if (name == "tool_cut") {
        const Field fields[] = {{"k_c_n_mm2", &s.tool_cut.k_c_n_mm2},
                                {"time_constant_s", &s.tool_cut.time_constant_s},
                                {"stiffness_n_per_mm_s", &s.tool_cut.stiffness_n_per_mm_s},
                                {"crash_speed_fraction", &s.tool_cut.crash_speed_fraction},
                                {"max_feed_per_tooth_mm", &s.tool_cut.max_feed_per_tooth_mm}};
        if (!read_section(key, name, node, fields)) return false;
      } else if (name == "boring") {
        const Field fields[] = {{"overhang_at_top_mm", &s.boring.overhang_at_top_mm},
                                {"gauge_top_depth_mm", &s.boring.gauge_top_depth_mm},
                                {"gauge_bottom_depth_mm", &s.boring.gauge_bottom_depth_mm},
                                {"sigma_d_um", &s.boring.sigma_d_um},
                                {"change_at_1", &s.boring.change_at_1},
                                {"change_at_2", &s.boring.change_at_2}};
        if (!read_section(key, name, node, fields)) return false;
      } else if (name == "probe") {
        const Field fields[] = {{"tip_radius_mm", &s.probe.tip_radius_mm}};
        if (!read_section(key, name, node, fields)) return false;
      } else if (name == "circle") {
        const Field fields[] = {{"radius_mm", &s.circle.radius_mm}, {"feed_mm_s", &s.circle.feed_mm_s},
                                {"ramp_s", &s.circle.ramp_s}, {"dwell_s", &s.circle.dwell_s}};
        if (!read_section(key, name, node, fields)) return false;
      } else {
        return unknown(key, name, node);
      }
    }
    return true;
  }

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
  bool read_plant(const toml::key& key, const toml::node& node, Scenario& s) {
    const toml::table* table = node.as_table();
    if (table == nullptr) return fail(key, "plant", std::string("expected a table, got ") + toml_type_name(node));
    for (auto&& [axis_key, axis_node] : *table) {
      const std::string path = "plant." + std::string(axis_key.str());
      if (axis_key.str() == "z") {
        // The vertical axis: the axis law's keys (no structural mode or screw
        // model on Z yet) and its own (z_axis_plant.hpp).
        ZAxisParams& z = s.z_axis;
        const Field z_fields[] = {{"tau_s", &z.plant.tau_s},
                                  {"gain", &z.plant.gain},
                                  {"coulomb_mm_s", &z.plant.coulomb_mm_s},
                                  {"stiction_mm_s", &z.plant.stiction_mm_s},
                                  {"stribeck_mm_s", &z.plant.stribeck_mm_s},
                                  {"accel_limit_mm_s2", &z.plant.accel_limit_mm_s2},
                                  {"gravity_mm_s", &z.gravity_mm_s},
                                  {"travel_top_mm", &z.travel_top_mm},
                                  {"travel_bottom_mm", &z.travel_bottom_mm},
                                  {"overtravel_mm", &z.overtravel_mm},
                                  {"home_switch_mm", &z.home_switch_mm}};
        if (!read_section(axis_key, path, axis_node, z_fields)) return false;
        continue;
      }
      AxisPlantParams* p = axis_key.str() == "x" ? &s.plant[0] : axis_key.str() == "y" ? &s.plant[1] : nullptr;
      if (p == nullptr) return unknown(axis_key, path, axis_node);
      const Field fields[] = {{"tau_s", &p->tau_s},
                              {"gain", &p->gain},
                              {"coulomb_mm_s", &p->coulomb_mm_s},
                              {"stiction_mm_s", &p->stiction_mm_s},
                              {"stribeck_mm_s", &p->stribeck_mm_s},
                              {"mode_hz", &p->mode_hz},
                              {"mode_zeta", &p->mode_zeta},
                              {"backlash_um", &p->backlash_um},
                              {"lead_error_um_per_m", &p->lead_error_um_per_m},
                              {"pitch_error_um", &p->pitch_error_um},
                              {"pitch_period_mm", &p->pitch_period_mm},
                              {"accel_limit_mm_s2", &p->accel_limit_mm_s2}};
      if (!read_section(axis_key, path, axis_node, fields)) return false;
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

  bool read_section(const toml::key& key, const std::string& path, const toml::node& node,
                    std::span<const Field> fields) {
    const toml::table* table = node.as_table();
    if (table == nullptr) return fail(key, path, std::string("expected a table, got ") + toml_type_name(node));
    for (auto&& entry : *table) {  // not a structured binding: clang 14 cannot capture one in a lambda
      const toml::key& field_key = entry.first;
      const toml::node& field_node = entry.second;
      const std::string field_path = path + "." + std::string(field_key.str());
      const Field* field = nullptr;
      for (const Field& f : fields) {
        if (f.name == field_key.str()) field = &f;
      }
      if (field == nullptr) return unknown(field_key, field_path, field_node);
      const bool ok = std::visit([&](auto* target) { return assign(field_key, field_path, field_node, target); },
                                 field->target);
      if (!ok) return false;
    }
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
