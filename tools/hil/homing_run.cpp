#include "tools/hil/homing_run.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "tools/hil/hil_rig.hpp"

namespace tnv::hil {

namespace {

// Portable uniform [0, 1) from a 64-bit generator (no library distribution).
double unit_interval(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }

constexpr double kSettleS = 0.2;        // at rest after homing before the judge looks
constexpr double kTimeoutS = 120.0;     // far beyond the cycle's own bounds
constexpr double kPowerUpRangeMm = 20.0;

// Motor-side position of the mark the cycle must latch: the first past the
// switch's release point in the back-off direction (away from the switch).
double expected_mark_mm(const emu::Scenario& s, const emu::Machine& m, hal::Axis axis) {
  const double lead_mm = s.encoder.lead_mm;
  const double phase_mm = m.index_mark_mm(axis);
  const double release_mm = s.board.home_mm(axis);
  const double k = (release_mm - phase_mm) / lead_mm;
  return phase_mm + lead_mm * (s.board.home_side(axis) < 0 ? std::floor(k) + 1.0 : std::ceil(k) - 1.0);
}

}  // namespace

emu::Scenario homing_scenario() {
  emu::Scenario s;
  s.name = "homing";
  s.board.axis[0].home_switch = true;
  s.board.axis[1].home_switch = true;
  s.board.axis[0].home_mm = -25.0;
  s.board.axis[1].home_mm = -25.0;
  // Marks 4.5 mm (x) and 6 mm (y) past the releases: far from them, whatever the phase of the count.
  s.board.axis[0].index_deg = 342.0;  // x marks at ... -20.5, -10.5 mm
  s.board.axis[1].index_deg = 36.0;   // y marks at ... -19, -9 mm
  // Z: its own switch at the top (the scenario's default: home_z_mm 0, side +1);
  // its marks 5 mm below the release, so the head backs off down onto one.
  const std::size_t z = hal::index(hal::Axis::z);
  s.board.axis[z].index_deg = 180.0;  // z marks at ... -5, 5 mm
  return s;
}

emu::Scenario with_homing_board(emu::Scenario table) {
  // A switch the default board does not have (or lacks one it has) is the table's own.
  const emu::BoardParams default_board{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    if (table.board.axis[i].home_switch != default_board.axis[i].home_switch) return table;
  const emu::Scenario board = homing_scenario();
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    table.board.axis[i].home_switch = board.board.axis[i].home_switch;
    table.board.axis[i].home_mm = board.board.axis[i].home_mm;
    table.board.axis[i].home_side = board.board.axis[i].home_side;
    table.board.axis[i].index_deg = board.board.axis[i].index_deg;
  }
  return table;
}

fw::FirmwareConfig homing_firmware_config() {
  fw::FirmwareConfig c = fw::default_firmware_config();
  for (fw::AxisConfig& a : c.axis) {  // (each axis' switch side: the machine's, fw::machine_homing_params)
    a.homing.search_mm_s = 10.0;
    a.homing.latch_mm_s = 2.0;
    a.homing.position_mm = -20.0;
    a.homing.search_max_mm = 100.0;
    a.homing.latch_max_mm = 15.0;
  }
  c.axis[hal::index(hal::Axis::z)].homing.position_mm = -5.0;  // Z's mark below its switch
  c.homing_required = true;
  return c;
}

HomingSeedResult run_homing_seed(const emu::Scenario& base_scenario, const fw::FirmwareConfig& config,
                                 std::uint32_t seed) {
  HomingSeedResult out;
  out.seed = seed;
  std::mt19937_64 g(seed);
  emu::Scenario s = base_scenario;
  // Every axis' power-up position, then every axis' count offset: for two
  // axes the draws of the seeds published so far.
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    s.board.axis[i].power_up_offset_mm = (2.0 * unit_interval(g) - 1.0) * kPowerUpRangeMm;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) s.encoder.axis_offset_counts[i] = unit_interval(g) * 65536.0;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    out.power_up_offset_mm[i] = s.board.axis[i].power_up_offset_mm;
    out.offset_counts[i] = s.encoder.axis_offset_counts[i];
  }

  std::string error;
  const std::unique_ptr<HilRig> rig = HilRig::create(s, config, config.axis[0].controller, error);
  if (!rig) {
    out.failure = error;
    return out;
  }
  rig->home();  // the firmware's first reading
  if (const fw::CommandStatus st = rig->task.home(hal::kEveryAxis); st != fw::CommandStatus::ok) {
    out.failure = std::string("home refused: ") + fw::to_string(st);
    return out;
  }
  const double start_s = rig->machine.time_s();
  while (rig->task.homing() && rig->machine.time_s() - start_s < kTimeoutS) rig->tick();
  out.time_s = rig->machine.time_s() - start_s;
  if (rig->task.fault().active()) {
    out.faulted = true;
    out.failure = std::string("fault ") + fw::to_string(rig->task.fault().reason) + " (axis " +
                  std::to_string(rig->task.fault().axis) + ")";
    return out;
  }
  for (const hal::Axis axis : hal::kAxes) {
    if (!rig->task.homed(axis)) {
      out.timed_out = rig->task.homing();
      out.failure = std::string(hal::axis_label(axis)) + " not homed: " +
                    fw::to_string(rig->task.homing_result(axis));
      return out;
    }
  }
  const int settle_ticks = static_cast<int>(kSettleS / kTickPeriodS);
  for (int k = 0; k < settle_ticks; ++k) rig->tick();
  for (const hal::Axis axis : hal::kAxes) {
    const std::size_t i = hal::index(axis);
    const double firmware_mm = rig->task.last_record().axis[i].position_mm - config.axis[i].homing.position_mm;
    const double motor_mm = rig->machine.truth(axis).motor_position_mm;
    const double truth_mm = motor_mm - expected_mark_mm(s, rig->machine, axis);
    const double reading_error_um = (firmware_mm - truth_mm) * 1000.0;
    // The present reading's own rounding (count = round(p / q + offset)) is
    // not the frame's: taken out, what is left is where the frame puts the mark.
    const double q_mm = s.encoder.count_mm();
    const double exact_counts = motor_mm / q_mm + s.encoder.offset_counts(axis);
    const double rounding_um = (static_cast<double>(std::llround(exact_counts)) - exact_counts) * q_mm * 1000.0;
    out.reading_error_um[i] = reading_error_um;
    out.home_error_um[i] = reading_error_um - rounding_um;
  }
  out.homed = true;
  return out;
}

HomingSummary run_homing(const emu::Scenario& scenario, const fw::FirmwareConfig& config, std::uint32_t seeds) {
  HomingSummary sum;
  bool any = false;
  std::array<double, hal::kAxisCount> min_um{}, max_um{};  // home error per axis over the homed seeds
  for (std::uint32_t seed = 1; seed <= seeds; ++seed) {
    const HomingSeedResult r = run_homing_seed(scenario, config, seed);
    sum.seeds.push_back(r);
    if (!r.homed) {
      sum.all_homed = false;
      continue;
    }
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      min_um[i] = any ? std::min(min_um[i], r.home_error_um[i]) : r.home_error_um[i];
      max_um[i] = any ? std::max(max_um[i], r.home_error_um[i]) : r.home_error_um[i];
      sum.home_error_um_max = std::max(sum.home_error_um_max, std::fabs(r.home_error_um[i]));
      sum.reading_error_um_max = std::max(sum.reading_error_um_max, std::fabs(r.reading_error_um[i]));
    }
    any = true;
    sum.time_s_max = std::max(sum.time_s_max, r.time_s);
  }
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    sum.home_error_spread_um = std::max(sum.home_error_spread_um, max_um[i] - min_um[i]);
  return sum;
}

}  // namespace tnv::hil
