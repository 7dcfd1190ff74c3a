#include "emulator/scenario_validation.hpp"

#include <charconv>
#include <cmath>
#include <numbers>

#include "emulator/scenario_keys.hpp"
#include "hal/axis.hpp"

namespace tnv::emu {

std::string format_number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

namespace {

class Rules {
 public:
  explicit Rules(const std::function<bool(std::string_view)>& given) : given_(given) {}

  std::optional<ScenarioViolation> found;

  // Physically plausible: finite, within [low, high], with the reason the range has.
  void plausible(const std::string& key, double value, double low, double high, const std::string& reason) {
    if (found || (std::isfinite(value) && value >= low && value <= high)) return;
    fail(key, "must be " + format_number(low) + ".." + format_number(high) + ": " + reason, value);
  }
  void non_negative(const std::string& key, double value) {
    if (!(std::isfinite(value) && value >= 0.0)) fail(key, "must be >= 0 and finite", value);
  }
  void int_range(const std::string& key, long long value, long long low, long long high) {
    if (value < low || value > high) {
      fail(key, "must be in " + std::to_string(low) + ".." + std::to_string(high), static_cast<double>(value));
    }
  }
  // low <= high for two keys; reported at whichever the file set (high first).
  void ordered(const std::string& low_key, double low, const std::string& high_key, double high) {
    if (found || low <= high) return;
    if (!is_given(high_key) && is_given(low_key)) {
      fail(low_key, "must be <= " + leaf(high_key) + " = " + format_number(high), low);
    } else {
      fail(high_key, "must be >= " + leaf(low_key) + " = " + format_number(low), high);
    }
  }
  bool is_given(const std::string& key) const { return given_ && given_(key); }
  void fail_text(const std::string& key, const std::string& message) {
    if (!found) found = ScenarioViolation{key, message};
  }

 private:
  void fail(const std::string& key, const std::string& rule, double got) {
    fail_text(key, rule + " (got " + format_number(got) + ")");
  }
  static std::string leaf(const std::string& key) { return key.substr(key.rfind('.') + 1); }

  const std::function<bool(std::string_view)>& given_;
};

// Each key's own range: the table's rule column (scenario_keys.cpp).
void check_each_key(Rules& r, const Scenario& s) {
  for (const ScenarioKey& key : scenario_keys()) {
    const std::optional<double> value = scenario_key_number(key, s);
    if (!value) continue;
    if (std::optional<std::string> why = key.rule.violation(*value)) {
      r.fail_text(key.path(), *why);
      return;
    }
  }
}

// Below: the rules between keys, after every key's own range.

void check_friction(Rules& r, const AxisPlantParams& p, const std::string& section) {
  r.ordered(section + ".coulomb_mm_s", p.coulomb_mm_s, section + ".stiction_mm_s", p.stiction_mm_s);
}

void check_z_axis(Rules& r, const ZAxisParams& z) {
  r.ordered("plant.z.travel_bottom_mm", z.travel_bottom_mm, "plant.z.travel_top_mm", z.travel_top_mm);
  if (!r.found && z.travel_bottom_mm == z.travel_top_mm)
    r.fail_text(r.is_given("plant.z.travel_top_mm") ? "plant.z.travel_top_mm" : "plant.z.travel_bottom_mm",
                "the travel must not be empty (travel_bottom_mm = travel_top_mm = " + format_number(z.travel_top_mm) + ")");
  r.plausible("plant.z.start_mm", z.start_mm, z.travel_bottom_mm, z.travel_top_mm, "a power-up position on the travel");
}

void check_stock(Rules& r, const StockParams& st) {
  r.ordered("stock.x_min_mm", st.x_min_mm, "stock.x_max_mm", st.x_max_mm);
  r.ordered("stock.y_min_mm", st.y_min_mm, "stock.y_max_mm", st.y_max_mm);
  if (!r.found && (st.x_min_mm == st.x_max_mm || st.y_min_mm == st.y_max_mm))
    r.fail_text(st.x_min_mm == st.x_max_mm ? "stock.x_max_mm" : "stock.y_max_mm",
                "the stock's rectangle must not be empty (min = max)");
  // [[stock.hole]] as the reader checks them, for scenarios built in code too.
  if (st.holes.size() > kMaxStockHoles) r.fail_text("stock.hole", "at most 64 holes");
  for (std::size_t i = 0; i < st.holes.size() && !r.found; ++i) {
    const StockHole& h = st.holes[i];
    const std::string at = "stock.hole[" + std::to_string(i) + "].";
    if (!std::isfinite(h.x_mm) || !std::isfinite(h.y_mm)) r.fail_text(at + "x_mm", "its axis must be finite");
    else if (!(h.diameter_mm > 0.0 && h.diameter_mm <= 500.0)) r.fail_text(at + "diameter_mm", "must be in (0, 500]");
    else if (!(h.depth_mm > 0.0)) r.fail_text(at + "depth_mm", "must be > 0 (infinite: through)");
  }
}

void check_boring(Rules& r, const Scenario& s) {
  const BoringAxesParams& b = s.boring;
  r.ordered("boring.gauge_top_depth_mm", b.gauge_top_depth_mm, "boring.gauge_bottom_depth_mm", b.gauge_bottom_depth_mm);
  if (r.found) return;
  if (!b.enabled) return;  // the gauge depths matter only to a bar that bores (a stock may take a short tool)
  if (!s.stock.enabled) {
    r.fail_text("boring.enabled", "the bore is in the stock: boring needs stock.enabled = true");
    return;
  }
  // The tool point reaches down to the bottom of Z's travel minus the tool's length.
  const double lowest_mm = s.z_axis.travel_bottom_mm - s.tool.length_mm;
  const double bottom_mm = s.stock.top_mm - b.gauge_bottom_depth_mm;
  if (bottom_mm < lowest_mm) {
    const std::string key = r.is_given("boring.gauge_bottom_depth_mm") ? "boring.gauge_bottom_depth_mm"
                            : r.is_given("tool.length_mm")             ? "tool.length_mm"
                            : r.is_given("stock.top_mm")               ? "stock.top_mm"
                                                                       : "plant.z.travel_bottom_mm";
    r.fail_text(key, "the bottom gauge depth must be within reach: stock.top_mm - boring.gauge_bottom_depth_mm = " +
                         format_number(bottom_mm) + " mm < plant.z.travel_bottom_mm - tool.length_mm = " +
                         format_number(lowest_mm) + " mm");
  }
}

// Read, work and write must fit in the tick: the transfers may take at most this much of its 1 ms.
constexpr double kMaxTransferUs = 900.0;

void check_io(Rules& r, const IoParams& io) {
  if (r.found) return;
  const double total_us = io.read_latency_us + io.write_latency_us + 2.0 * io.jitter_us;
  if (total_us > kMaxTransferUs) {
    const std::string key = r.is_given("io.jitter_us")        ? "io.jitter_us"
                            : r.is_given("io.write_latency_us") ? "io.write_latency_us"
                                                                : "io.read_latency_us";
    r.fail_text(key, "the transfers must leave the firmware room in the 1 ms tick: read_latency_us + "
                     "write_latency_us + 2 jitter_us = " + format_number(total_us) + " us > 900 us");
  }
}

void check_board(Rules& r, const BoardParams& b) {
  for (const hal::Axis axis : hal::kAxes) {
    const BoardAxisParams& a = b.axis[hal::index(axis)];
    const std::string n = hal::axis_label(axis);
    r.ordered("board.limit_" + n + "_min_mm", a.limit_min_mm, "board.limit_" + n + "_max_mm", a.limit_max_mm);
  }
}

void check_circle(Rules& r, const CircleParams& c) {
  if (r.found) return;
  // Each raised-cosine ramp covers F ramp / 2 of arc.
  const double ramps_mm = c.feed_mm_s * c.ramp_s;
  const double circle_mm = 2.0 * std::numbers::pi * c.radius_mm;
  if (ramps_mm > circle_mm) {
    const std::string key = r.is_given("circle.ramp_s")     ? "circle.ramp_s"
                            : r.is_given("circle.feed_mm_s") ? "circle.feed_mm_s"
                                                             : "circle.radius_mm";
    r.fail_text(key, "both ramps must fit in the circle: feed_mm_s * ramp_s = " + format_number(ramps_mm) +
                         " mm > 2 pi radius_mm = " + format_number(circle_mm) + " mm");
  }
}

constexpr double kMaxFaultTimeS = 1e9;  // 31 years of machine time

void check_faults(Rules& r, const Scenario& s) {
  const std::uint32_t max_code = (std::uint32_t{1} << (s.dac.bits >= 8 && s.dac.bits <= 16 ? s.dac.bits : 16)) - 1;
  for (std::size_t i = 0; i < s.faults.size() && !r.found; ++i) {
    const FaultSpec& f = s.faults[i];
    const std::string key = "fault[" + std::to_string(i) + "].";
    const FaultKeys keys = fault_keys(f.kind);
    r.non_negative(key + "start_s", f.start_s);
    if (keys.duration) r.non_negative(key + "duration_s", f.duration_s);
    // The timeline counts 10 us sub-steps in a uint64 (found by fuzzing: start_s = 5e25 overflowed it).
    if (f.start_s > kMaxFaultTimeS) r.fail_text(key + "start_s", "must be <= 1e9 s (got " + format_number(f.start_s) + ")");
    if (keys.duration && f.duration_s > kMaxFaultTimeS)
      r.fail_text(key + "duration_s", "must be <= 1e9 s (got " + format_number(f.duration_s) + ")");
    if (keys.code) r.int_range(key + "code", f.dac_code, 0, max_code);
    if (keys.ticks) r.int_range(key + "ticks", f.ticks, 1, kMaxMissedTicks);
    if (keys.counts) {
      r.int_range(key + "counts", f.counts, -kMaxEncoderJumpCounts, kMaxEncoderJumpCounts);
      if (f.counts == 0) r.fail_text(key + "counts", "must be nonzero (got 0)");
    }
    if (keys.delay && !(std::isfinite(f.delay_us) && f.delay_us > 0.0 && f.delay_us <= kMaxLateTickDelayUs)) {
      r.fail_text(key + "delay_us", "must be > 0 and <= " + std::to_string(static_cast<long long>(kMaxLateTickDelayUs)) + " (got " +
                                        format_number(f.delay_us) + ")");
    }
  }
}

}  // namespace

std::optional<ScenarioViolation> find_scenario_violation(const Scenario& s,
                                                         const std::function<bool(std::string_view)>& given) {
  Rules r(given);
  check_each_key(r, s);
  for (const hal::Axis axis : hal::kAxes)
    check_friction(r, s.plant[hal::index(axis)], "plant." + std::string(hal::axis_label(axis)));
  check_board(r, s.board);
  check_z_axis(r, s.z_axis);
  check_stock(r, s.stock);
  check_boring(r, s);
  check_io(r, s.io);
  check_circle(r, s.circle);
  check_faults(r, s);
  return r.found;
}

std::string validate_scenario(const Scenario& scenario) {
  const auto violation = find_scenario_violation(scenario);
  return violation ? violation->key + ": " + violation->message : std::string{};
}

}  // namespace tnv::emu
