// Frequency-response estimation (issue 17, tools/tune): on records of a
// known discrete loop, simulated exactly, the estimates of the plant, the
// open loop and the closed loop equal the transfer functions, the margins
// read off sampled points equal loop_analysis.hpp's, and bad records are
// refused.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "firmware/compensation/excitation_signal.hpp"
#include "firmware/control/loop_analysis.hpp"
#include "tools/tune/bode_margins.hpp"
#include "tools/tune/freq_response.hpp"
#include "tools/tune/freq_response_model.hpp"
#include "tools/tune/freq_response_smoothing.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tools/tune/freq_response_spectra.hpp"

namespace tnv::tune {
namespace {

constexpr double kEstTickS = 1e-3;

// The loop of freq_response_model.hpp's implemented view, simulated: the
// controller fed [p_k, (p_k - p_{k-1}) / T], u = c + d.
LoopRecord simulate_freq_loop(const LoopModel& m, const fw::MultisineTones& tones, double rms, int periods) {
  fw::Multisine d;
  d.start(tones, rms);
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  Eigen::Vector3d xi = Eigen::Vector3d::Zero();
  double p_prev = 0.0;
  LoopRecord r;
  r.period_s = kEstTickS;
  const std::int64_t n = tones.period_ticks * periods;
  for (std::int64_t k = 0; k < n; ++k) {
    const Eigen::Vector2d seen(x(0), (x(0) - p_prev) / kEstTickS);
    const double c = (m.controller.Cc * xi + m.controller.Dc * seen).value();
    const double dk = d.sample(k);
    const double u = c + dk;
    r.excitation_mm_s.push_back(dk);
    r.controller_mm_s.push_back(c);
    r.applied_mm_s.push_back(u);
    r.position_mm.push_back(x(0));
    xi = m.controller.Ac * xi + m.controller.Bc * seen;
    p_prev = x(0);
    x = m.plant.A * x + m.plant.B * u;
  }
  return r;
}

LoopModel freq_pid_loop() {
  LoopModel m;
  m.plant = fw::zoh_axis_model(0.00536, 1.0, kEstTickS);
  m.controller = fw::linear_pid(m.plant, 300.0, 5000.0, 1.0, 0.0);
  m.measured_speed = true;
  return m;
}

TEST(FreqResponseEstimator, MultisineRecordOfAKnownLoopGivesItsTransferFunctionsExactly) {
  const LoopModel m = freq_pid_loop();
  const fw::MultisineTones tones = fw::multisine_tones(2.0, 300.0, 25, kEstTickS);
  ASSERT_EQ(tones.count, 25u);
  // 12 periods, the first 6 dropped: the closed loop's transient (poles inside
  // radius ~0.9) has died out to rounding.
  const LoopRecord r = simulate_freq_loop(m, tones, 1.0, 12);
  const std::vector<std::int32_t> h(tones.harmonic.begin(), tones.harmonic.begin() + tones.count);
  const std::vector<SpectraPoint> s = multisine_spectra(r, tones.period_ticks, h, 6);
  ASSERT_EQ(s.size(), 25u);
  EXPECT_EQ(s[0].averages, 6);
  for (const LoopKind kind : {LoopKind::plant, LoopKind::open, LoopKind::closed}) {
    const std::vector<ResponsePoint> est = loop_response(s, kind);
    for (const ResponsePoint& p : est) {
      const std::complex<double> want = model_response(m, kind, p.freq_hz);
      EXPECT_LT(std::abs(p.response / want - 1.0), 1e-6)
          << to_string(kind) << " at " << p.freq_hz << " Hz: " << gain_db(p.response) << " dB "
          << phase_deg(p.response) << " deg, model " << gain_db(want) << " dB " << phase_deg(want) << " deg";
      EXPECT_GT(p.coherence, 1.0 - 1e-9) << to_string(kind) << " at " << p.freq_hz << " Hz: noise-free record";
    }
  }
}

TEST(FreqResponseEstimator, NoiseOutsideTheExcitationLowersTheCoherence) {
  const LoopModel m = freq_pid_loop();
  const fw::MultisineTones tones = fw::multisine_tones(5.0, 200.0, 20, kEstTickS);
  LoopRecord r = simulate_freq_loop(m, tones, 1.0, 20);
  // A deterministic, aperiodic disturbance on the measured position only.
  for (std::size_t k = 0; k < r.position_mm.size(); ++k)
    r.position_mm[k] += 2e-3 * std::sin(0.7371 * static_cast<double>(k) * static_cast<double>(k) * 1e-3);
  const std::vector<std::int32_t> h(tones.harmonic.begin(), tones.harmonic.begin() + tones.count);
  const std::vector<ResponsePoint> plant = loop_response(multisine_spectra(r, tones.period_ticks, h, 4), LoopKind::plant);
  double lowest = 1.0;
  for (const ResponsePoint& p : plant) lowest = std::fmin(lowest, p.coherence);
  EXPECT_LT(lowest, 0.99) << "the disturbance left every tone's coherence at 1";
  EXPECT_GE(lowest, 0.0);
}

TEST(FreqResponseEstimator, MarginsFromDensePointsMatchLoopAnalysis) {
  LoopModel m;
  m.plant = fw::paper_axis_model(hal::Axis::x);
  m.controller = fw::linear_pid(m.plant, 300.0, 5000.0, 1.0, 0.0);
  m.measured_speed = false;  // the design view is loop_analysis.hpp's
  const fw::LoopMargins want = fw::loop_margins(m.plant, m.controller);
  ASSERT_TRUE(want.crossover_found);
  const ModelMargins got = model_margins(m);
  ASSERT_TRUE(got.margins.crossover_found);
  const double want_hz = want.crossover_rad_s / (2.0 * std::numbers::pi);
  EXPECT_NEAR(got.margins.crossover_hz, want_hz, 1e-3 * want_hz) << "Hz";
  EXPECT_NEAR(got.margins.phase_margin_deg, want.phase_margin_deg, 0.05) << "deg";
  if (std::isfinite(want.gain_margin_db))
    EXPECT_NEAR(got.margins.gain_margin_db, want.gain_margin_db, 0.05) << "dB";
  else
    EXPECT_FALSE(std::isfinite(got.margins.gain_margin_db));
  EXPECT_GT(got.bandwidth_hz, 0.0);
}

// The smoothing margins are read through: on the model's own points (every
// harmonic of 10 Hz, 10 .. 450 Hz) it moves no margin by more than 0.5 %;
// on points with scatter of low coherence it brings them closer to the
// truth.
TEST(FreqResponseEstimator, SmoothingKeepsASmoothResponseAndShrinksScatter) {
  for (const hal::Axis axis : {hal::Axis::x, hal::Axis::y}) {
    LoopModel m;
    const fw::AxisConfig config = fw::default_firmware_config().axis[hal::index(axis)];
    // The reference table's speed loop (emulator/scenario.hpp): 5.36 ms on x, 7.122 ms on y.
    m.plant = fw::zoh_axis_model(axis == hal::Axis::x ? 0.00536 : 0.007122, 1.0, kEstTickS);
    m.controller = active_linear_controller(config);
    std::vector<double> freqs;
    for (int k = 1; k <= 45; ++k) freqs.push_back(10.0 * k);
    const std::vector<ResponsePoint> truth = model_points(m, LoopKind::open, freqs);
    const BodeMargins raw = margins_from_points(truth);
    const BodeMargins smooth = margins_from_points(smoothed_response(truth, 3));
    ASSERT_TRUE(raw.crossover_found && smooth.crossover_found);
    ASSERT_TRUE(std::isfinite(raw.gain_margin_db)) << "a phase crossover below 450 Hz";
    EXPECT_NEAR(smooth.crossover_hz, raw.crossover_hz, 0.005 * raw.crossover_hz);
    EXPECT_NEAR(smooth.phase_margin_deg, raw.phase_margin_deg, 0.005 * raw.phase_margin_deg);
    EXPECT_NEAR(smooth.gain_margin_db, raw.gain_margin_db, 0.005 * raw.gain_margin_db);

    std::vector<ResponsePoint> noisy = truth;
    std::uint32_t state = 12345u;
    const auto uniform = [&state] {  // a fixed LCG: the same scatter every run
      state = state * 1664525u + 1013904223u;
      return static_cast<double>(state >> 8) / static_cast<double>(1u << 24) - 0.5;
    };
    for (ResponsePoint& p : noisy) {
      p.response *= std::complex<double>(1.0 + 0.2 * uniform(), 0.2 * uniform());
      p.coherence = 0.5;
    }
    const std::vector<ResponsePoint> smoothed = smoothed_response(noisy, 3);
    double raw_err = 0.0, smooth_err = 0.0;
    for (std::size_t i = 0; i < truth.size(); ++i) {
      raw_err += std::norm(noisy[i].response / truth[i].response - 1.0);
      smooth_err += std::norm(smoothed[i].response / truth[i].response - 1.0);
      EXPECT_EQ(smoothed[i].freq_hz, noisy[i].freq_hz);
      EXPECT_EQ(smoothed[i].coherence, noisy[i].coherence);
    }
    EXPECT_LT(smooth_err, 0.5 * raw_err);
  }
  EXPECT_EQ(smoothed_response({}, 3).size(), 0u);
}

TEST(FreqResponseEstimator, WelchOnASweepRecordApproachesThePlant) {
  const LoopModel m = freq_pid_loop();
  fw::LogSweep sweep;
  sweep.start(5.0, 150.0, 8.0, 2.0, kEstTickS);
  LoopRecord r;
  r.period_s = kEstTickS;
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  for (std::int64_t k = 0; k < 8000; ++k) {
    const double u = sweep.sample(k);
    r.excitation_mm_s.push_back(u);
    r.applied_mm_s.push_back(u);
    r.controller_mm_s.push_back(0.0);
    r.position_mm.push_back(x(0));
    x = m.plant.A * x + m.plant.B * u;
  }
  const std::vector<ResponsePoint> p = loop_response(welch_spectra(r, {10.0, 30.0, 80.0}, 1000), LoopKind::plant);
  for (const ResponsePoint& q : p) {
    const std::complex<double> want = plant_response(m.plant, q.freq_hz);
    EXPECT_NEAR(gain_db(q.response), gain_db(want), 0.5) << q.freq_hz << " Hz";
    EXPECT_NEAR(phase_deg(q.response / want), 0.0, 3.0) << q.freq_hz << " Hz";
  }
}

TEST(FreqResponseEstimator, BadRecordsAreRefused) {
  LoopRecord r;
  r.excitation_mm_s.assign(100, 0.0);
  r.applied_mm_s.assign(100, 0.0);
  r.controller_mm_s.assign(99, 0.0);
  r.position_mm.assign(100, 0.0);
  EXPECT_THROW(multisine_spectra(r, 10, {1}, 0), std::invalid_argument) << "series of different lengths";
  r.controller_mm_s.assign(100, 0.0);
  EXPECT_THROW(multisine_spectra(r, 1, {1}, 0), std::invalid_argument) << "period of 1 tick";
  EXPECT_THROW(multisine_spectra(r, 50, {1}, 2), std::invalid_argument) << "2 periods, both skipped";
  EXPECT_THROW(welch_spectra(r, {10.0}, 200), std::invalid_argument) << "no whole segment";
  EXPECT_THROW(welch_spectra(r, {600.0}, 50), std::invalid_argument) << "above Nyquist";
  LoopKind k = LoopKind::plant;
  EXPECT_FALSE(parse_loop_kind("bode", k));
  EXPECT_TRUE(parse_loop_kind("closed", k));
  EXPECT_EQ(k, LoopKind::closed);
}

}  // namespace
}  // namespace tnv::tune
