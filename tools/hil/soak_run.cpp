#include "tools/hil/soak_run.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <utility>

#include "emulator/quadrature_encoder.hpp"
#include "hal/io_board_registers.hpp"
#include "tools/hil/command_status_text.hpp"
#include "tools/hil/hil_firmware_config.hpp"
#include "tools/hil/hil_rig.hpp"

namespace tnv::hil {

namespace {

constexpr std::int64_t kEncoderModulus = std::int64_t{1} << hal::regs::kEncoderBits;

std::int64_t ticks_for(double seconds) { return static_cast<std::int64_t>(std::llround(seconds / kTickPeriodS)); }

std::int64_t floor_div(std::int64_t a, std::int64_t b) { return a / b - ((a % b != 0) && ((a < 0) != (b < 0))); }

// Runs the cycles and does the per-tick bookkeeping.
class SoakBench {
 public:
  SoakBench(HilRig& rig, const SoakRequest& request, SoakResult& result)
      : rig_(rig),
        request_(request),
        result_(result),
        encoders_{make_encoders()} {}

  bool cycle() {
    SoakCycle c;
    c.start_s = rig_.machine.time_s();
    cycle_ = &c;
    const bool ok = circle(c) && hold(request_.rest_s) && rest_sample(c) &&
                    jog(hal::Axis::x, request_.jog_speed_mm_s) && jog(hal::Axis::x, -request_.jog_speed_mm_s) &&
                    jog(hal::Axis::y, request_.jog_speed_mm_s) && jog(hal::Axis::y, -request_.jog_speed_mm_s) &&
                    hold(0.2);
    c.clock_wraps = result_.clock_wraps;
    cycle_ = nullptr;
    if (ok) result_.cycles.push_back(c);
    return ok;
  }

 private:
  std::array<emu::QuadratureEncoder, hal::kAxisCount> make_encoders() const {
    return [this]<std::size_t... I>(std::index_sequence<I...>) {
      return std::array<emu::QuadratureEncoder, hal::kAxisCount>{make_encoder(hal::kAxes[I])...};
    }(std::make_index_sequence<hal::kAxisCount>{});
  }

  emu::QuadratureEncoder make_encoder(hal::Axis axis) const {
    const emu::Scenario& s = request_.scenario;
    return emu::QuadratureEncoder(s.encoder.count_mm(), s.encoder.offset_counts(axis));
  }

  std::uint32_t board_register(std::uint16_t word) {
    std::uint32_t value = 0;
    rig_.machine.read_register(word, value);
    return value;
  }

  bool tick() {
    rig_.tick();
    fw::TickTask& task = rig_.task;
    if (task.state() == fw::MotionState::faulted) {
      const fw::FaultRecord& f = task.fault();
      result_.error = std::string("fault: ") + fw::to_string(f.reason) + " at tick " + std::to_string(f.tick);
      return false;
    }
    // The board's own count of ticks and wraps of its 32-bit clock.
    const std::uint32_t sequence = board_register(hal::regs::kTickSequence);
    const std::uint32_t clock = board_register(hal::regs::kTickClock);
    if (ticks_ == 0) {
      first_sequence_ = sequence;
    } else if (clock < last_clock_) {
      ++result_.clock_wraps;
      result_.clock_wrap_s.push_back(rig_.machine.time_s());
    }
    last_clock_ = clock;
    ++ticks_;
    result_.board_ticks = std::uint64_t{sequence - first_sequence_} + 1;
    // The firmware's tick count against the board's clock: one period per tick.
    const auto clock_drift = static_cast<std::int64_t>(rig_.machine.elapsed_clocks()) -
                             static_cast<std::int64_t>(task.counters().ticks) * 10'000;
    result_.max_clock_drift_clocks = std::max<std::int64_t>(result_.max_clock_drift_clocks, std::llabs(clock_drift));
    // The firmware's extended encoder count against the true count (the
    // board's decoder, unwrapped), both since power-up.
    const fw::TickRecord& rec = task.last_record();
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      const hal::Axis axis = hal::axis_from_index(i);
      const std::int64_t true_count = encoders_[i].count(rig_.machine.truth(axis).position_mm);
      if (ticks_ == 1) {
        first_count_[i] = true_count;
      } else if (floor_div(true_count, kEncoderModulus) != floor_div(last_count_[i], kEncoderModulus)) {
        ++result_.encoder_register_wraps;
      }
      last_count_[i] = true_count;
      const fw::AxisConfig& ac = task.config().axis[i];
      const std::int64_t firmware_count = std::llround((rec.axis[i].position_mm - ac.home_position_mm) / ac.count_mm);
      result_.max_encoder_drift_counts =
          std::max<std::int64_t>(result_.max_encoder_drift_counts, std::llabs(firmware_count - (true_count - first_count_[i])));
      const double d_hat = std::fabs(rec.axis[i].d_hat_mm_s);
      result_.max_abs_d_hat_mm_s = std::max(result_.max_abs_d_hat_mm_s, d_hat);
      if (cycle_ != nullptr) cycle_->max_abs_d_hat_mm_s[i] = std::max(cycle_->max_abs_d_hat_mm_s[i], d_hat);
    }
    if (request_.progress && ticks_ % progress_every_ == 0) {
      request_.progress(rig_.machine.time_s(), request_.duration_s);
    }
    return true;
  }

  bool refused(const char* what, fw::CommandStatus st) {
    result_.error = std::string(what) + " refused: " + command_status_text(st, rig_.task);
    return false;
  }

  bool circle(SoakCycle& c) {
    fw::TickTask& task = rig_.task;
    if (const fw::CommandStatus st = task.start_circle(circle_spec_for(request_.scenario)); st != fw::CommandStatus::ok)
      return refused("start_circle", st);
    ContourAccumulator contour;
    const std::int64_t limit = task.motion_ticks() + ticks_for(request_.scenario.circle.dwell_s) + 1000;
    for (std::int64_t k = 0; task.state() != fw::MotionState::holding; ++k) {
      if (k > limit) {
        result_.error = "a circle did not finish in time";
        return false;
      }
      if (!tick()) return false;
      const fw::TickRecord& rec = task.last_record();
      if (rec.motion_tick >= 0) {
        contour.add(contour_error_mm(rec.axis[0].reference_mm, rec.axis[1].reference_mm, rec.axis[0].position_mm,
                                     rec.axis[1].position_mm));
      }
    }
    c.circle = contour.stats();
    return true;
  }

  bool hold(double seconds) {
    for (std::int64_t k = 0; k < ticks_for(seconds); ++k)
      if (!tick()) return false;
    return true;
  }

  bool rest_sample(SoakCycle& c) {
    const fw::TickRecord& rec = rig_.task.last_record();
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      c.rest_error_um[i] = (rec.axis[i].reference_mm - rec.axis[i].position_mm) * 1e3;
      c.rest_d_hat_mm_s[i] = rec.axis[i].d_hat_mm_s;
      result_.max_rest_error_um = std::max(result_.max_rest_error_um, std::fabs(c.rest_error_um[i]));
    }
    return true;
  }

  // The operator holds the jog key for jog_s (re-sent every tick), lets go,
  // and waits for the axis to come to rest.
  bool jog(hal::Axis axis, double speed_mm_s) {
    fw::TickTask& task = rig_.task;
    const std::size_t a = hal::index(axis);
    const auto track = [&] {
      const fw::AxisTickRecord& r = task.last_record().axis[a];
      cycle_->jog_max_following_um =
          std::max(cycle_->jog_max_following_um, std::fabs(r.reference_mm - r.position_mm) * 1e3);
    };
    for (std::int64_t k = 0; k < ticks_for(request_.jog_s); ++k) {
      if (const fw::CommandStatus st = task.jog(axis, speed_mm_s); st != fw::CommandStatus::ok)
        return refused("jog", st);
      if (!tick()) return false;
      track();
    }
    if (const fw::CommandStatus st = task.jog(axis, 0.0); st != fw::CommandStatus::ok) return refused("jog release", st);
    for (std::int64_t k = 0; task.state() != fw::MotionState::holding; ++k) {
      if (k > 5000) {
        result_.error = "a jog did not come to rest";
        return false;
      }
      if (!tick()) return false;
      track();
    }
    return true;
  }

  HilRig& rig_;
  const SoakRequest& request_;
  SoakResult& result_;
  std::array<emu::QuadratureEncoder, hal::kAxisCount> encoders_;
  SoakCycle* cycle_ = nullptr;
  std::uint64_t ticks_ = 0;
  std::uint32_t first_sequence_ = 0;
  std::uint32_t last_clock_ = 0;
  std::array<std::int64_t, hal::kAxisCount> first_count_{};
  std::array<std::int64_t, hal::kAxisCount> last_count_{};
  std::uint64_t progress_every_ = std::max<std::uint64_t>(
      1000, static_cast<std::uint64_t>(request_.duration_s / kTickPeriodS / 100.0));
};

SoakMetric metric(const std::vector<SoakCycle>& cycles, std::size_t first, std::size_t count,
                  const std::function<double(const SoakCycle&)>& value) {
  SoakMetric m;
  if (count == 0) return m;
  double sum = 0.0;
  for (std::size_t k = first; k < first + count; ++k) sum += value(cycles[k]);
  m.mean = sum / static_cast<double>(count);
  if (count < 2) return m;
  double sq = 0.0;
  for (std::size_t k = first; k < first + count; ++k) sq += (value(cycles[k]) - m.mean) * (value(cycles[k]) - m.mean);
  m.std = std::sqrt(sq / static_cast<double>(count - 1));
  return m;
}

// The mean of |v| over the axes (added in list order: for two axes the
// (|x| + |y|) / 2 of before, bit for bit).
double mean_abs(const std::array<double, hal::kAxisCount>& v) {
  double sum = 0.0;
  for (const double a : v) sum += std::fabs(a);
  return sum / static_cast<double>(hal::kAxisCount);
}

SoakWindow window(const std::vector<SoakCycle>& cycles, std::size_t first, std::size_t count) {
  SoakWindow w;
  w.cycles = count;
  w.contour_max_um = metric(cycles, first, count, [](const SoakCycle& c) { return c.circle.max_um; });
  w.contour_mean_um = metric(cycles, first, count, [](const SoakCycle& c) { return c.circle.mean_um; });
  w.contour_std_um = metric(cycles, first, count, [](const SoakCycle& c) { return c.circle.std_um; });
  w.rest_error_um = metric(cycles, first, count, [](const SoakCycle& c) { return mean_abs(c.rest_error_um); });
  w.rest_d_hat_mm_s = metric(cycles, first, count, [](const SoakCycle& c) { return mean_abs(c.rest_d_hat_mm_s); });
  w.cycle_d_hat_mm_s = metric(cycles, first, count, [](const SoakCycle& c) {
    return *std::max_element(c.max_abs_d_hat_mm_s.begin(), c.max_abs_d_hat_mm_s.end());
  });
  return w;
}

bool same(const SoakMetric& first, const SoakMetric& last, std::size_t n, const SoakLimits& lim, double absolute) {
  const double standard_error = std::sqrt((first.std * first.std + last.std * last.std) / static_cast<double>(n));
  const double allowed = std::max({absolute, lim.relative * std::fabs(first.mean), lim.standard_errors * standard_error});
  return std::fabs(last.mean - first.mean) <= allowed;
}

}  // namespace

SoakResult run_soak(const SoakRequest& request, const fw::FirmwareConfig& base_config) {
  SoakResult result;
  const emu::Scenario& s = request.scenario;
  if (s.cutting.enabled || s.milling.enabled) {
    result.error = "soak: scenario " + s.name + " cuts; the emulator cuts wherever the table moves, jogs too (use no-cut)";
    return result;
  }
  if (!s.faults.empty()) {
    result.error = "soak: scenario " + s.name + " injects faults; a soak runs a healthy machine";
    return result;
  }
  if (!(std::isfinite(request.duration_s) && request.duration_s > 0.0)) {
    result.error = "soak: duration must be > 0";
    return result;
  }
  std::unique_ptr<HilRig> rig = HilRig::create(s, base_config, request.controller, result.error);
  if (!rig) return result;
  rig->home();
  SoakBench bench(*rig, request, result);
  bool ok = true;
  while (ok && rig->machine.time_s() < request.duration_s) ok = bench.cycle();
  result.simulated_s = rig->machine.time_s();
  result.firmware_ticks = rig->task.counters().ticks;
  result.counters = rig->task.counters();
  result.completed = ok;

  const std::size_t n = result.cycles.size();
  const SoakLimits& lim = result.limits;
  const std::size_t k = std::min(lim.max_window_cycles, n / 3);
  result.first = window(result.cycles, 0, k);
  result.last = window(result.cycles, n - k, k);
  // The homing ticks run before the bench counts; the board saw them too.
  result.no_missed_ticks = result.counters.missed_ticks == 0 && result.counters.late_ticks == 0 &&
                           result.counters.bus_errors == 0 &&
                           result.board_ticks + HilRig::kHomingTicks == result.firmware_ticks;
  result.no_counter_drift = result.max_encoder_drift_counts == 0 && result.max_clock_drift_clocks == 0;
  const SoakWindow& f = result.first;
  const SoakWindow& l = result.last;
  result.stationary = k >= 2 && same(f.contour_max_um, l.contour_max_um, k, lim, lim.contour_abs_um) &&
                      same(f.contour_mean_um, l.contour_mean_um, k, lim, lim.contour_abs_um) &&
                      same(f.contour_std_um, l.contour_std_um, k, lim, lim.contour_abs_um) &&
                      same(f.rest_error_um, l.rest_error_um, k, lim, lim.rest_error_abs_um) &&
                      same(f.rest_d_hat_mm_s, l.rest_d_hat_mm_s, k, lim, lim.d_hat_abs_mm_s) &&
                      same(f.cycle_d_hat_mm_s, l.cycle_d_hat_mm_s, k, lim, lim.d_hat_abs_mm_s);
  return result;
}

}  // namespace tnv::hil
