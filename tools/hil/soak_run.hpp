#pragma once
// Soak: the real firmware on the emulated board for a long simulated run,
// cycle after cycle of the S1 circle and operator jogs, long enough to wrap
// the 32-bit 10 MHz tick counter (every 429.5 s) several times. Checked
// every tick: no tick missed or late, the firmware's extended encoder count
// equal to the board's true count, the firmware's tick count equal to the
// board's clock. Checked per cycle: contour statistics, position error and
// the DDC's disturbance estimate at rest, so the first and last cycles can
// be compared (stationarity, no integrator drift).
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "emulator/scenario.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/tick_record.hpp"
#include "hal/axis.hpp"
#include "tools/score/contour_stats.hpp"

namespace tnv::hil {

struct SoakRequest {
  // Friction only: the emulator cuts wherever the table moves (it has no
  // stock to be outside of), so the 30 mm/s jogs would cut at 15 times the
  // circle's load; [cutting] and [milling] are refused (and so are [[fault]]s).
  emu::Scenario scenario;
  fw::ControllerKind controller = fw::ControllerKind::rdvsc;
  double duration_s = 3600.0;  // simulated; the cycle under way when it is reached runs to its end
  double jog_speed_mm_s = 30.0;
  double jog_s = 0.4;   // each jog leg: key held this long, then released
  double rest_s = 1.0;  // holding after each circle, before the rest sample
  std::function<void(double done_s, double total_s)> progress;  // every ~1% of duration_s
};

struct SoakCycle {
  double start_s = 0.0;  // machine time the circle was commanded
  ContourStats circle{};  // S1 eq. (33) over the circle's motion
  // Per axis, indexed by hal::index(axis):
  std::array<double, hal::kAxisCount> rest_error_um{};       // reference - measured position at the end of the rest
  std::array<double, hal::kAxisCount> rest_d_hat_mm_s{};     // the DDC's disturbance estimate then
  std::array<double, hal::kAxisCount> max_abs_d_hat_mm_s{};  // over the whole cycle
  double jog_max_following_um = 0.0;           // |reference - measured| during the jogs
  std::uint32_t clock_wraps = 0;               // TICK_CLOCK wraps so far
};

// One per-cycle figure over a window of cycles.
struct SoakMetric {
  double mean = 0.0;
  double std = 0.0;  // sample standard deviation (0 for one cycle)
};

// The first / last third of the cycles (at most max_window_cycles each).
struct SoakWindow {
  std::size_t cycles = 0;
  SoakMetric contour_max_um{};
  SoakMetric contour_mean_um{};
  SoakMetric contour_std_um{};
  SoakMetric rest_error_um{};     // |reference - position| at rest, mean over the axes
  SoakMetric rest_d_hat_mm_s{};   // |d_hat| at rest, mean over the axes
  SoakMetric cycle_d_hat_mm_s{};  // max |d_hat| over the cycle, worse axis
};

// Stationary: for every metric the last window's mean is within the largest
// of an absolute figure, a share of the first window's mean, and a number
// of standard errors of the difference (the cycles scatter: the circle
// starts where stiction left the table, a fraction of a count apart).
struct SoakLimits {
  double relative = 0.10;
  double standard_errors = 3.0;
  double contour_abs_um = 0.1;
  double rest_error_abs_um = 0.42;  // one count
  double d_hat_abs_mm_s = 0.2;
  std::size_t max_window_cycles = 20;
};

struct SoakResult {
  bool completed = false;  // ran to the end without a fault or a refused command
  std::string error;
  double simulated_s = 0.0;
  std::uint64_t firmware_ticks = 0;
  std::uint64_t board_ticks = 0;  // TICK_SEQUENCE advance seen at the board, first tick to last
  fw::TickCounters counters{};
  std::uint32_t clock_wraps = 0;
  std::vector<double> clock_wrap_s;  // machine time of the first tick after each wrap
  std::uint32_t encoder_register_wraps = 0;  // 16-bit encoder register wraps, both axes
  std::int64_t max_encoder_drift_counts = 0;  // |firmware count - board's true count|, worst tick
  std::int64_t max_clock_drift_clocks = 0;    // |elapsed clocks - 10,000 x ticks|, worst tick
  double max_abs_d_hat_mm_s = 0.0;
  double max_rest_error_um = 0.0;
  std::vector<SoakCycle> cycles;
  SoakWindow first{};
  SoakWindow last{};
  SoakLimits limits{};
  // The verdicts, each of which can fail.
  bool no_missed_ticks = false;  // missed, late and bus errors all 0, board ticks = firmware ticks
  bool no_counter_drift = false;
  bool stationary = false;

  bool passed() const noexcept { return completed && no_missed_ticks && no_counter_drift && stationary; }
};

SoakResult run_soak(const SoakRequest& request, const fw::FirmwareConfig& base_config);

}  // namespace tnv::hil
