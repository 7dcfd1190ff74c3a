#include "tools/hil/arsc_tick_study.hpp"

#include <cmath>
#include <optional>

#include "drivers/emulated/emulated_register_bus.hpp"
#include "drivers/fpga/fpga_io_board.hpp"
#include "emulator/force_adc.hpp"
#include "emulator/machine.hpp"
#include "emulator/scenario_validation.hpp"
#include "firmware/adaptive/arsc/robust_arsc.hpp"
#include "firmware/io/dac_code.hpp"
#include "firmware/timing/encoder_position.hpp"

namespace tnv::hil {

namespace {

using hal::Axis;

// The rig: machine, bus, driver; X enabled, Y left off.
class MillingRig {
 public:
  explicit MillingRig(const emu::Scenario& s) : machine_(s), bus_(machine_), board_(bus_) {}
  bool init(std::string& error) {
    if (const drivers::FpgaInitResult r = board_.init({}); !r.ok()) {
      error = std::string("I/O board: ") + r.message;
      return false;
    }
    machine_.advance_to_next_tick();
    board_.read_inputs();
    encoder_.reset(board_.latched_count(Axis::x));
    return true;
  }
  // One 1 ms tick: read, then write `command_mm_s` to X.
  void tick(double command_mm_s) {
    machine_.advance_to_next_tick();
    board_.read_inputs();
    encoder_.update(board_.latched_count(Axis::x));
    board_.set_code(Axis::x, fw::speed_to_dac_code(command_mm_s, dac_));
    board_.set_servo_enable(Axis::x, true);
    board_.kick();
    board_.write_outputs();
  }
  double position_mm() const { return static_cast<double>(encoder_.counts()) * count_mm_; }
  double force_n() const {
    const double volts = static_cast<double>(board_.latched_force_code()) * emu::kAdcFullScaleV /
                         static_cast<double>((1u << hal::regs::kAdcBits) - 1);
    return volts / machine_.scenario().force_sensor.volts_per_n;
  }
  emu::Machine& machine() { return machine_; }

 private:
  emu::Machine machine_;
  drivers::EmulatedRegisterBus bus_;
  drivers::FpgaIoBoard board_;
  fw::EncoderPosition encoder_{hal::regs::kEncoderBits};
  fw::DacScale dac_{};
  double count_mm_ = 10.0 / 24000.0;
};

}  // namespace

emu::Scenario tick_study_scenario(const emu::MillingParams& milling) {
  emu::Scenario s;
  s.name = "mill-x";
  s.milling = milling;
  s.milling.enabled = true;
  return s;
}

TickStudyResult run_tick_study(const TickStudyConfig& c) {
  TickStudyResult r;
  r.config = c;
  const double period_s = 1e-3 * static_cast<double>(c.ticks_per_sample);
  const double lambda = std::exp(-period_s / c.memory_s);

  // Test-and-learning stage: constant start depth, two-level input around 40 mm/s.
  {
    emu::MillingParams m = c.milling;
    m.depth = {c.milling.depth.start_mm, c.milling.depth.start_mm, 0.0, 0.0};
    const emu::Scenario s = tick_study_scenario(m);
    if (const std::string bad = emu::validate_scenario(s); !bad.empty()) {
      r.error = "scenario: " + bad;
      return r;
    }
    MillingRig rig(s);
    if (!rig.init(r.error)) return r;
    const auto samples = static_cast<std::size_t>(c.test_stage_s / period_s);
    const std::size_t hold = std::max<std::size_t>(1, static_cast<std::size_t>(0.3 / period_s));
    const std::vector<double> u = test_stage_input(samples, 4.0, 1.0, hold, 11);
    std::vector<TestStageSample> data;
    double last_position = rig.position_mm();
    for (std::size_t n = 0; n < samples; ++n) {
      const double f = rig.force_n() / c.force_ref_n;
      const double v = (rig.position_mm() - last_position) / period_s / c.feed_ref_mm_s;
      last_position = rig.position_mm();
      data.push_back({f, v, u[n]});
      for (std::uint32_t k = 0; k < c.ticks_per_sample; ++k) rig.tick(u[n] * c.feed_ref_mm_s);
    }
    data.erase(data.begin(), data.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(data.size(), 5)));
    r.test_stage = fit_structured_model(data, true);
  }

  using namespace fw::arsc;
  RobustArscConfig ac;
  const Poles7 mapped = poles_at_period(paper_poles(c.poles), period_s * c.pole_speedup);
  if (c.keep_fast_poles) {
    // Delay state at 0, drive at its own pole, the force loop on four paper poles (two pairs for case3/4).
    const Poles6 six{0.0, -r.test_stage.model.drive.a11, mapped[3], mapped[4], mapped[5], mapped[6]};
    ac.d_star = desired_coefficients(six);
    ac.fixed.gamma03 = std::pow(ac.fixed.gamma03, period_s / kPaperSamplePeriod_s);
  } else {
    ac.d_star = desired_coefficients(six_of_seven(mapped));
  }
  ac.drive = r.test_stage.model.drive;
  ac.estimator.a21 = r.test_stage.model.a21;
  ac.estimator.initial_gain = std::max(r.test_stage.model.cutting_gain, 2e-3 * r.test_stage.model.cutting_gain);
  ac.estimator.gain_min = 0.02 * ac.estimator.initial_gain;
  ac.estimator.gain_max = 50.0 * ac.estimator.initial_gain;
  ac.estimator.forgetting = lambda;
  ac.estimator.initial_covariance = 1.0;
  ac.estimator.max_covariance = 1.0e3;
  ac.estimator.min_feed = 0.05;
  ac.limits.max_gain = 1.0e7;  // at 1 ms g is ~1e-3 (normalised): the gains are large by construction
  ac.force_ref = 1.0;
  ac.u_limit = 16.0;  // 160 mm/s: the DAC's range
  if (const fw::ParamCheck p = validate(ac); !p.ok) {
    r.error = std::string("ARSC config: ") + p.field + ": " + p.reason;
    return r;
  }
  RobustArsc arsc(ac);
  if (!arsc.signals().have_gains) {
    r.error = std::string("no gains for the identified model: ") + to_string(arsc.signals().last_reason);
    return r;
  }

  {
    const ArscGains& g = arsc.signals().gains;
    r.initial_gamma01 = g.gamma01;
    for (double x : {g.k, g.gamma11, g.gamma13, g.gamma22, g.gamma31, g.gamma32})
      r.initial_max_abs_gain = std::max(r.initial_max_abs_gain, std::fabs(x));
  }
  const emu::Scenario s = tick_study_scenario(c.milling);
  if (const std::string bad = emu::validate_scenario(s); !bad.empty()) {
    r.error = "scenario: " + bad;
    return r;
  }
  MillingRig rig(s);
  if (!rig.init(r.error)) return r;
  const double start_mm = rig.position_mm();
  const auto ticks = static_cast<std::uint64_t>(c.duration_s * 1000.0);
  double command_mm_s = 0.0, pending_mm_s = 0.0, last_position = rig.position_mm();
  double sum_sq = 0.0;
  std::uint64_t scored = 0;
  for (std::uint64_t k = 0; k < ticks; ++k) {
    const double t_s = static_cast<double>(k) * 1e-3;
    const double force_n = rig.force_n();
    if (k % c.ticks_per_sample == 0) {
      const double f = force_n / c.force_ref_n;
      const double v = (rig.position_mm() - last_position) / period_s / c.feed_ref_mm_s;
      last_position = rig.position_mm();
      command_mm_s = pending_mm_s;  // computed one ARSC sample ago
      const double ramp = c.soft_start_s > 0.0 ? std::min(1.0, (t_s + period_s) / c.soft_start_s) : 1.0;
      arsc.set_force_ref(ramp);
      pending_mm_s = arsc.step(f, v) * c.feed_ref_mm_s;
      if (r.first_saturation_s < 0.0 && std::fabs(pending_mm_s) >= ac.u_limit * c.feed_ref_mm_s) r.first_saturation_s = t_s;
    }
    if (t_s >= c.settle_s) {
      const double e = std::fabs(force_n - c.force_ref_n) / c.force_ref_n * 100.0;
      r.force_error_max_pct = std::max(r.force_error_max_pct, e);
      sum_sq += e * e;
      ++scored;
    }
    if (k % 10 == 0) {
      const emu::AxisTruth truth = rig.machine().truth(Axis::x);
      r.trace.push_back({t_s, rig.machine().milling_depth_mm(), force_n, truth.speed_mm_s, command_mm_s,
                         arsc.model().cutting_gain});
    }
    if (!std::isfinite(force_n) || force_n > 20.0 * c.force_ref_n) {
      r.diverged = true;
      break;
    }
    rig.tick(command_mm_s);
  }
  r.force_error_rms_pct = scored ? std::sqrt(sum_sq / static_cast<double>(scored)) : 0.0;
  r.travel_mm = rig.position_mm() - start_mm;
  const auto& counts = arsc.signals().reason_counts;
  for (std::size_t i = 1; i < counts.size(); ++i) r.refused_updates += counts[i];
  return r;
}

}  // namespace tnv::hil
