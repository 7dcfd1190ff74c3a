#include "emulator/scenario_validation.hpp"

#include <charconv>
#include <cmath>
#include <numbers>

#include "emulator/substep_timing.hpp"

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

  void positive(const std::string& key, double value) {
    if (!(std::isfinite(value) && value > 0.0)) fail(key, "must be > 0 and finite", value);
  }
  void non_negative(const std::string& key, double value) {
    if (!(std::isfinite(value) && value >= 0.0)) fail(key, "must be >= 0 and finite", value);
  }
  void finite(const std::string& key, double value) {
    if (!std::isfinite(value)) fail(key, "must be finite", value);
  }
  void below(const std::string& key, double value, double limit, const std::string& what) {
    if (!(std::isfinite(value) && value >= 0.0 && value < limit)) fail(key, "must be >= 0 and below " + what, value);
  }
  // Physically plausible: finite, within [low, high], with the reason the range has.
  void plausible(const std::string& key, double value, double low, double high, const std::string& reason) {
    if (found || (std::isfinite(value) && value >= low && value <= high)) return;
    fail(key, "must be " + format_number(low) + ".." + format_number(high) + ": " + reason, value);
  }
  void int_range(const std::string& key, long long value, long long low, long long high) {
    if (value < low || value > high) {
      fail(key, "must be in " + std::to_string(low) + ".." + std::to_string(high), static_cast<double>(value));
    }
  }
  void at_least(const std::string& key, long long value, long long low) {
    if (value < low) fail(key, "must be >= " + std::to_string(low), static_cast<double>(value));
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

void check_plant(Rules& r, const AxisPlantParams& p, const std::string& section) {
  r.positive(section + ".tau_s", p.tau_s);
  r.positive(section + ".gain", p.gain);
  r.non_negative(section + ".coulomb_mm_s", p.coulomb_mm_s);
  r.non_negative(section + ".stiction_mm_s", p.stiction_mm_s);
  r.ordered(section + ".coulomb_mm_s", p.coulomb_mm_s, section + ".stiction_mm_s", p.stiction_mm_s);
  r.positive(section + ".stribeck_mm_s", p.stribeck_mm_s);
  const double nyquist_hz = static_cast<double>(kSubstepsPerSecond) / 2.0;
  r.below(section + ".mode_hz", p.mode_hz, nyquist_hz, "the sub-step Nyquist frequency " + format_number(nyquist_hz) + " Hz");
  r.below(section + ".mode_zeta", p.mode_zeta, 1.0, "1");
  // Beyond these the model is no servo table: the numbers would only make
  // the run fail later, far from the key that caused it.
  r.plausible(section + ".tau_s", p.tau_s, 1e-4, 1.0, "a servo axis' speed loop settles in 0.1 ms to 1 s");
  r.plausible(section + ".gain", p.gain, 0.1, 10.0, "the drive's speed per commanded speed");
  r.plausible(section + ".coulomb_mm_s", p.coulomb_mm_s, 0.0, 1000.0, "friction above 1000 mm/s is no moving table (a jam is 200)");
  r.plausible(section + ".stiction_mm_s", p.stiction_mm_s, 0.0, 1000.0, "friction above 1000 mm/s is no moving table (a jam is 200)");
  r.plausible(section + ".stribeck_mm_s", p.stribeck_mm_s, 0.0, 1000.0, "the Stribeck speed of a table's guideways");
  r.plausible(section + ".backlash_um", p.backlash_um, 0.0, 500.0,
              "a ball screw's lost motion: 0-5 um new, 10-50 um worn; past 0.5 mm the nut is broken");
  r.plausible(section + ".lead_error_um_per_m", p.lead_error_um_per_m, -1000.0, 1000.0,
              "a ball screw's cumulative lead error (ISO 3408-3 class C10 allows 700 um/m)");
  r.plausible(section + ".pitch_error_um", p.pitch_error_um, 0.0, 100.0,
              "a ball screw's periodic lead error amplitude (C5 varies 8 um within a turn)");
  r.plausible(section + ".pitch_period_mm", p.pitch_period_mm, 0.1, 1000.0, "a screw lead or a multiple of it");
  if (!r.found && !(p.accel_limit_mm_s2 == 0.0 || (p.accel_limit_mm_s2 >= 100.0 && p.accel_limit_mm_s2 <= 1e6))) {
    // (NaN fails both tests)
    r.fail_text(section + ".accel_limit_mm_s2",
                "must be 0 (none) or 100..1e+06: a servo axis' current-limited acceleration, 0.01 to 100 g (got " +
                    format_number(p.accel_limit_mm_s2) + ")");
  }
}

// A machining centre of the TNV-40 class: Z travel well under 1 m.
constexpr double kMachineRangeMm = 1000.0;

void check_z_axis(Rules& r, const ZAxisParams& z) {
  check_plant(r, z.plant, "plant.z");
  r.plausible("plant.z.gravity_mm_s", z.gravity_mm_s, -100.0, 100.0,
              "what the counterbalance leaves of the head's weight, as a table speed");
  r.plausible("plant.z.travel_top_mm", z.travel_top_mm, -kMachineRangeMm, kMachineRangeMm, "machine coordinates");
  r.plausible("plant.z.travel_bottom_mm", z.travel_bottom_mm, -kMachineRangeMm, kMachineRangeMm, "machine coordinates");
  r.ordered("plant.z.travel_bottom_mm", z.travel_bottom_mm, "plant.z.travel_top_mm", z.travel_top_mm);
  if (!r.found && z.travel_bottom_mm == z.travel_top_mm)
    r.fail_text(r.is_given("plant.z.travel_top_mm") ? "plant.z.travel_top_mm" : "plant.z.travel_bottom_mm",
                "the travel must not be empty (travel_bottom_mm = travel_top_mm = " + format_number(z.travel_top_mm) + ")");
  r.plausible("plant.z.overtravel_mm", z.overtravel_mm, 0.0, 100.0, "the room between a travel end and its hard stop");
  r.plausible("plant.z.home_switch_mm", z.home_switch_mm, z.travel_bottom_mm, z.travel_top_mm + z.overtravel_mm,
              "a home switch between the bottom of the travel and the top hard stop");
}

void check_spindle(Rules& r, const SpindleParams& sp) {
  r.plausible("spindle.tau_s", sp.tau_s, 1e-3, 10.0, "a spindle drive's speed loop settles in 1 ms to 10 s");
  r.int_range("spindle.dac_bits", sp.dac_bits, 8, 16);
  r.plausible("spindle.full_scale_v", sp.full_scale_v, 0.5, 50.0, "a drive's analogue speed reference (10 V class)");
  r.plausible("spindle.rpm_at_full_scale", sp.rpm_at_full_scale, 1.0, 100'000.0, "a machining spindle's speed");
  r.plausible("spindle.accel_limit_rpm_s", sp.accel_limit_rpm_s, 1.0, 1e6,
              "a spindle drive's current-limited acceleration (thousands of rpm/s)");
  r.plausible("spindle.droop_rpm_per_n", sp.droop_rpm_per_n, 0.0, 100.0, "speed lost per newton of cutting load");
  if (!r.found && (sp.encoder_counts_per_rev <= 0 || sp.encoder_counts_per_rev % 4 != 0))
    r.fail_text("spindle.encoder_counts_per_rev", "must be a positive multiple of 4 (x4 decoding) (got " +
                                                      std::to_string(sp.encoder_counts_per_rev) + ")");
  r.int_range("spindle.encoder_counts_per_rev", sp.encoder_counts_per_rev, 4, 1'000'000);
  r.plausible("spindle.index_deg", sp.index_deg, 0.0, 360.0, "a spindle angle in degrees");
}

void check_tool_and_stock(Rules& r, const Scenario& s) {
  r.plausible("tool.diameter_mm", s.tool.diameter_mm, 0.1, 100.0, "an end mill's diameter");
  r.int_range("tool.flutes", s.tool.flutes, 1, 20);
  r.plausible("tool.flute_length_mm", s.tool.flute_length_mm, 0.1, 300.0, "an end mill's flute length");
  r.plausible("tool.length_mm", s.tool.length_mm, 0.0, 500.0, "spindle nose to tool point");
  r.plausible("stock.top_mm", s.stock.top_mm, -kMachineRangeMm, kMachineRangeMm, "machine coordinates");
  const auto side = [&r](const char* key, double value) {
    // The default rectangle is unbounded (the whole table): +-inf are allowed.
    if (!r.found && !(std::isinf(value) || (value >= -kMachineRangeMm && value <= kMachineRangeMm)))
      r.fail_text(key, "must be -1000..1000 (machine coordinates) or +-inf (unbounded) (got " + format_number(value) + ")");
  };
  side("stock.x_min_mm", s.stock.x_min_mm);
  side("stock.x_max_mm", s.stock.x_max_mm);
  side("stock.y_min_mm", s.stock.y_min_mm);
  side("stock.y_max_mm", s.stock.y_max_mm);
  r.ordered("stock.x_min_mm", s.stock.x_min_mm, "stock.x_max_mm", s.stock.x_max_mm);
  r.ordered("stock.y_min_mm", s.stock.y_min_mm, "stock.y_max_mm", s.stock.y_max_mm);
  if (!r.found && (s.stock.x_min_mm == s.stock.x_max_mm || s.stock.y_min_mm == s.stock.y_max_mm))
    r.fail_text(s.stock.x_min_mm == s.stock.x_max_mm ? "stock.x_max_mm" : "stock.y_max_mm",
                "the stock's rectangle must not be empty (min = max)");
  r.plausible("tool_cut.k_c_n_mm2", s.tool_cut.k_c_n_mm2, 1.0, 20'000.0,
              "a specific cutting force (aluminium ~700, steel ~2000 N/mm^2)");
  r.plausible("tool_cut.time_constant_s", s.tool_cut.time_constant_s, 1e-4, 100.0, "a cutting process' time constant");
  r.plausible("tool_cut.stiffness_n_per_mm_s", s.tool_cut.stiffness_n_per_mm_s, 0.1, 1e6,
              "a drive's stiffness against a load, newtons per mm/s");
  r.plausible("tool_cut.crash_speed_fraction", s.tool_cut.crash_speed_fraction, 0.0, 1.0,
              "a fraction of the commanded spindle speed");
  r.plausible("tool_cut.max_feed_per_tooth_mm", s.tool_cut.max_feed_per_tooth_mm, 1e-3, 10.0, "a chip thickness");
  r.plausible("probe.tip_radius_mm", s.probe.tip_radius_mm, 0.0, 10.0, "a touch probe's stylus ball radius");
}

void check_boring(Rules& r, const Scenario& s) {
  const BoringAxesParams& b = s.boring;
  r.plausible("boring.overhang_at_top_mm", b.overhang_at_top_mm, 1.0, 2000.0, "a boring bar's overhang");
  r.plausible("boring.gauge_top_depth_mm", b.gauge_top_depth_mm, 0.0, kMachineRangeMm, "a depth below the stock top");
  r.plausible("boring.gauge_bottom_depth_mm", b.gauge_bottom_depth_mm, 0.0, kMachineRangeMm, "a depth below the stock top");
  r.ordered("boring.gauge_top_depth_mm", b.gauge_top_depth_mm, "boring.gauge_bottom_depth_mm", b.gauge_bottom_depth_mm);
  r.plausible("boring.sigma_d_um", b.sigma_d_um, 0.0, 1000.0, "the process noise on the bar's deflection");
  r.int_range("boring.change_at_1", b.change_at_1, 0, 1'000'000);
  r.int_range("boring.change_at_2", b.change_at_2, 0, 1'000'000);
  if (r.found) return;
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

void check_noise(Rules& r, const NoiseParams& n) {
  r.plausible("noise.force_adc_v_rms", n.force_adc_v_rms, 0.0, 1.0,
              "noise at the force ADC's input (its 0-10 V range has a 2.4 mV LSB)");
  r.plausible("noise.accel_g_rms", n.accel_g_rms, 0.0, 1.0, "a MEMS accelerometer's noise over the tick bandwidth (mg class)");
  r.plausible("noise.accel_bias_g", n.accel_bias_g, -1.0, 1.0, "an accelerometer's zero-g offset (tens of mg)");
  r.plausible("noise.dac_offset_v", n.dac_offset_v, -1.0, 1.0, "a speed DAC's offset (mV class; 1 V is a tenth of full scale)");
  r.plausible("noise.dac_gain_error", n.dac_gain_error, -0.1, 0.1, "a DAC's relative gain error (0.1-1 % class)");
  r.plausible("noise.encoder_glitch_per_s", n.encoder_glitch_per_s, 0.0, 1000.0,
              "miscounts per second (a thousand a second is a broken cable)");
  r.int_range("noise.encoder_glitch_counts", n.encoder_glitch_counts, 1, 1000);
  r.plausible("noise.bore_gauge_um_rms", n.bore_gauge_um_rms, 0.0, 50.0,
              "a bore gauge's repeatability (um class; 50 um is a tenth of a millimetre band)");
  r.plausible("noise.bore_gauge_resolution_um", n.bore_gauge_resolution_um, 0.0, 100.0,
              "a bore gauge's reading step (0.1-10 um)");
}

// Read, work and write must fit in the tick: the transfers may take at most this much of its 1 ms.
constexpr double kMaxTransferUs = 900.0;

void check_io(Rules& r, const IoParams& io) {
  r.plausible("io.read_latency_us", io.read_latency_us, 0.0, 500.0,
              "a register transport's read after the latch (SPI or Ethernet: tens to hundreds of us)");
  r.plausible("io.write_latency_us", io.write_latency_us, 0.0, 500.0,
              "a register transport's write (SPI or Ethernet: tens to hundreds of us)");
  r.plausible("io.jitter_us", io.jitter_us, 0.0, 200.0, "a Linux board's transfer jitter (tens of us)");
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

// A table of the TNV-40 class travels well under 1 m: switches beyond +-500 mm are typing errors.
constexpr double kSwitchRangeMm = 500.0;

void check_board(Rules& r, const BoardParams& b) {
  // Each check once per axis; the keys are the file's (board.home_x_mm, ...).
  for (const hal::Axis axis : hal::kAxes)
    r.plausible("board.home_" + std::string(hal::axis_label(axis)) + "_mm", b.axis[hal::index(axis)].home_mm,
                -kSwitchRangeMm, kSwitchRangeMm, "a home switch on the table's travel");
  for (const hal::Axis axis : hal::kAxes) {
    const BoardAxisParams& a = b.axis[hal::index(axis)];
    const std::string n = hal::axis_label(axis);
    if (a.home_side != -1 && a.home_side != 1)
      r.fail_text("board.home_" + n + "_side", "must be -1 (asserted at and below home_" + n +
                                                   "_mm) or 1 (at and above) (got " + std::to_string(a.home_side) + ")");
  }
  for (const hal::Axis axis : hal::kAxes) {
    const std::string n = hal::axis_label(axis);
    r.plausible("board.index_" + n + "_deg", b.axis[hal::index(axis)].index_deg, 0.0, 360.0, "a motor angle in degrees");
  }
  for (const hal::Axis axis : hal::kAxes) {
    const BoardAxisParams& a = b.axis[hal::index(axis)];
    const std::string n = hal::axis_label(axis);
    r.plausible("board.limit_" + n + "_min_mm", a.limit_min_mm, -kSwitchRangeMm, kSwitchRangeMm,
                "a limit switch on the table's travel");
    r.plausible("board.limit_" + n + "_max_mm", a.limit_max_mm, -kSwitchRangeMm, kSwitchRangeMm,
                "a limit switch on the table's travel");
  }
  for (const hal::Axis axis : hal::kAxes) {
    const BoardAxisParams& a = b.axis[hal::index(axis)];
    const std::string n = hal::axis_label(axis);
    r.ordered("board.limit_" + n + "_min_mm", a.limit_min_mm, "board.limit_" + n + "_max_mm", a.limit_max_mm);
  }
  for (const hal::Axis axis : hal::kAxes)
    r.plausible("board.power_up_offset_" + std::string(hal::axis_label(axis)) + "_mm",
                b.axis[hal::index(axis)].power_up_offset_mm, -kSwitchRangeMm, kSwitchRangeMm,
                "where the table stands at power-up, on its travel");
}

void check_circle(Rules& r, const CircleParams& c) {
  r.positive("circle.radius_mm", c.radius_mm);
  r.positive("circle.feed_mm_s", c.feed_mm_s);
  r.non_negative("circle.ramp_s", c.ramp_s);
  r.non_negative("circle.dwell_s", c.dwell_s);
  r.plausible("circle.radius_mm", c.radius_mm, 1e-3, 500.0, "a circle the table's travel can hold");
  r.plausible("circle.feed_mm_s", c.feed_mm_s, 1e-3, 1000.0, "a contouring feed up to 60 m/min");
  r.plausible("circle.ramp_s", c.ramp_s, 0.0, 3600.0, "an hour at most");
  r.plausible("circle.dwell_s", c.dwell_s, 0.0, 3600.0, "an hour at most");
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
  check_plant(r, s.plant[0], "plant.x");
  check_plant(r, s.plant[1], "plant.y");

  r.positive("cutting.spindle_rpm", s.cutting.spindle_rpm);
  r.at_least("cutting.flutes", s.cutting.flutes, 1);
  r.non_negative("cutting.mean_mm_s", s.cutting.mean_mm_s);
  r.non_negative("cutting.amplitude_mm_s", s.cutting.amplitude_mm_s);
  r.finite("cutting.exponent", s.cutting.exponent);
  r.finite("cutting.phase_rad", s.cutting.phase_rad);
  r.plausible("cutting.spindle_rpm", s.cutting.spindle_rpm, 1.0, 100'000.0, "a machining spindle's speed");
  r.plausible("cutting.mean_mm_s", s.cutting.mean_mm_s, 0.0, 1000.0, "a cutting load as a table speed");
  r.plausible("cutting.amplitude_mm_s", s.cutting.amplitude_mm_s, 0.0, 1000.0, "a cutting load as a table speed");
  r.plausible("cutting.exponent", s.cutting.exponent, -10.0, 10.0, "the spindle-speed law's exponent");

  if (s.encoder.counts_per_rev <= 0 || s.encoder.counts_per_rev % 4 != 0) {
    r.fail_text("encoder.counts_per_rev", "must be a positive multiple of 4 (x4 decoding) (got " +
                                               std::to_string(s.encoder.counts_per_rev) + ")");
  }
  r.positive("encoder.lead_mm", s.encoder.lead_mm);
  r.plausible("encoder.lead_mm", s.encoder.lead_mm, 0.1, 100.0, "a ball screw's lead");
  r.plausible("encoder.counts_per_rev", s.encoder.counts_per_rev, 4.0, 1e8, "a rotary encoder's counts per turn (x4)");
  for (const hal::Axis axis : hal::kAxes)
    r.finite("encoder.offset_counts_" + std::string(hal::axis_label(axis)), s.encoder.offset_counts(axis));

  check_board(r, s.board);

  r.int_range("dac.bits", s.dac.bits, 8, 16);
  r.positive("dac.full_scale_v", s.dac.full_scale_v);
  r.positive("dac.rpm_at_full_scale", s.dac.rpm_at_full_scale);
  r.plausible("dac.full_scale_v", s.dac.full_scale_v, 0.5, 50.0, "a servo's analogue speed reference (10 V class)");
  r.plausible("dac.rpm_at_full_scale", s.dac.rpm_at_full_scale, 1.0, 100'000.0, "a servo motor's speed");

  r.non_negative("force_sensor.volts_per_mm_s", s.force_sensor.volts_per_mm_s);
  r.non_negative("force_sensor.volts_per_n", s.force_sensor.volts_per_n);
  r.positive("milling.time_constant_s", s.milling.time_constant_s);
  r.non_negative("milling.force_n_per_mm_mm_s", s.milling.force_n_per_mm_mm_s);
  r.non_negative("milling.feed_load_mm_s_per_n", s.milling.feed_load_mm_s_per_n);
  r.non_negative("milling.depth_start_mm", s.milling.depth.start_mm);
  r.non_negative("milling.depth_peak_mm", s.milling.depth.peak_mm);
  r.non_negative("milling.rise_s", s.milling.depth.rise_s);
  r.non_negative("milling.fall_s", s.milling.depth.fall_s);
  r.plausible("force_sensor.volts_per_mm_s", s.force_sensor.volts_per_mm_s, 0.0, 1000.0, "a force sensor's output range");
  r.plausible("force_sensor.volts_per_n", s.force_sensor.volts_per_n, 0.0, 1000.0, "a force sensor's output range");
  r.plausible("milling.time_constant_s", s.milling.time_constant_s, 1e-4, 100.0, "a cutting process' time constant");
  r.plausible("milling.depth_start_mm", s.milling.depth.start_mm, 0.0, 100.0, "a depth of cut");
  r.plausible("milling.depth_peak_mm", s.milling.depth.peak_mm, 0.0, 100.0, "a depth of cut");

  check_z_axis(r, s.z_axis);
  check_spindle(r, s.spindle);
  check_tool_and_stock(r, s);
  check_boring(r, s);
  check_noise(r, s.noise);
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
