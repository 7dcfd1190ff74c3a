#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstring>
#include <iomanip>
#include <numbers>
#include <vector>

#include "firmware/control/linear_controller.hpp"
#include "firmware/control/loop_analysis.hpp"
#include "firmware/control/pid_tuning.hpp"

namespace tnv::fw {
namespace {

TEST(PidTuning, PidLoopHasTheDvscCrossoverAndTheCappedPhaseMarginAndIsStable) {
  for (hal::Axis axis : hal::kAxes) {
    const char name = hal::axis_name(axis);
    const PidTuningReport r = paper_pid_tuning(axis);
    ASSERT_TRUE(r.ok) << name << ": " << r.note;
    EXPECT_GT(std::strlen(r.rule), 20u);
    EXPECT_NEAR(r.pid_crossover_rad_s / r.dvsc_crossover_rad_s, 1.0, 0.01)
        << name << ": PID crossover " << r.pid_crossover_hz << " Hz, DVSC+DDC " << r.dvsc_crossover_hz << " Hz";
    EXPECT_NEAR(r.dvsc_crossover_hz, r.dvsc_crossover_rad_s / (2 * std::numbers::pi), 1e-9);
    // The paper's parameters (X, Y) give DVSC+DDC margins above 60 deg:
    // capped. Z's (the autotune rule's g = 0.3) give 56.3 deg: the PID gets
    // the DVSC+DDC's own margin.
    if (axis == hal::Axis::x || axis == hal::Axis::y) {
      EXPECT_GT(r.dvsc_phase_margin_deg, 60.0) << name;
      EXPECT_TRUE(r.phase_margin_capped) << name;
    }
    EXPECT_TRUE(r.phase_margin_reached) << name;
    EXPECT_DOUBLE_EQ(r.target_phase_margin_deg, std::min(r.dvsc_phase_margin_deg, 60.0)) << name;
    EXPECT_GT(r.target_phase_margin_deg, 45.0) << name;
    EXPECT_NEAR(r.pid_phase_margin_deg, r.target_phase_margin_deg, 0.1)
        << name << ": PID phase margin " << r.pid_phase_margin_deg << " deg";
    EXPECT_TRUE(r.pid_closed_loop_stable) << name << ": spectral radius " << r.pid_closed_loop_spectral_radius;
    EXPECT_LT(r.pid_closed_loop_spectral_radius, 1.0);
    EXPECT_LT(r.dvsc_closed_loop_spectral_radius, 1.0);
    EXPECT_GT(r.pid_gain_margin_db, 6.0) << name << ": PID gain margin " << r.pid_gain_margin_db << " dB";
    EXPECT_GT(r.dvsc_gain_margin_db, 6.0) << name << ": DVSC+DDC gain margin " << r.dvsc_gain_margin_db << " dB";
    for (double g : {r.kp, r.ki, r.kd}) {
      EXPECT_TRUE(std::isfinite(g)) << name;
      EXPECT_GT(g, 0.0) << name;
    }
    EXPECT_NEAR(r.ti_s, 4.0 * r.td_s, 1e-15);
    EXPECT_NEAR(r.ki, r.kp / r.ti_s, 1e-9 * r.ki);
    EXPECT_NEAR(r.kd, r.kp * r.td_s, 1e-12 * r.kd);
    EXPECT_EQ(r.derivative_filter_tf_s, 0.0);
  }
}

TEST(PidTuning, PidLoopGainIsUnityWithTheTargetPhaseAtTheDvscCrossover) {
  for (hal::Axis axis : {hal::Axis::x, hal::Axis::y}) {
    const AxisModel m = paper_axis_model(axis);
    const PidTuningReport r = paper_pid_tuning(axis);
    const std::complex<double> l =
        loop_gain(m, linear_pid(m, r.kp, r.ki, r.kd, r.derivative_filter_tf_s), r.dvsc_crossover_rad_s);
    EXPECT_NEAR(std::abs(l), 1.0, 1e-9);
    EXPECT_NEAR(180.0 + std::arg(l) * 180.0 / std::numbers::pi, 60.0, 1e-6);
  }
}

TEST(PidTuning, DefaultPidParamsAreTheTunedXAxisGains) {
  const PidTuningReport r = paper_pid_tuning(hal::Axis::x);
  const PidParams def{};
  EXPECT_NEAR(def.kp, r.kp, 1e-4 * r.kp) << "update the PidParams defaults: kp = " << r.kp;
  EXPECT_NEAR(def.ki, r.ki, 1e-4 * r.ki) << "update the PidParams defaults: ki = " << r.ki;
  EXPECT_NEAR(def.kd, r.kd, 1e-4 * r.kd) << "update the PidParams defaults: kd = " << r.kd;
  EXPECT_EQ(def.derivative_filter_tf_s, r.derivative_filter_tf_s);
  EXPECT_TRUE(def.feedforward);
}

// default_firmware_config() takes the papers' gains precomputed; they must be
// the tuner's, to the last bit where the tuner's arithmetic is the one they
// were printed from (x86-64, no FMA contraction; elsewhere the contraction
// moves its last bits).
TEST(PidTuning, PrecomputedPaperGainsAreTheTunersGains) {
  for (hal::Axis axis : hal::kAxes) {
    const char name = hal::axis_name(axis);
    const PidTuningReport r = paper_pid_tuning(axis);
    ASSERT_TRUE(r.ok) << name << ": " << r.note;
    const PidParams tuned = pid_params_from(r, 123.0);
    const PidParams precomputed = paper_pid_params(axis, 123.0);
#if defined(__x86_64__)
    EXPECT_EQ(precomputed, tuned) << name << ": update paper_pid_params: kp = " << std::setprecision(17) << r.kp
                                  << ", ki = " << r.ki << ", kd = " << r.kd;
#else
    EXPECT_NEAR(precomputed.kp, tuned.kp, 1e-9 * tuned.kp) << name;
    EXPECT_NEAR(precomputed.ki, tuned.ki, 1e-9 * tuned.ki) << name;
    EXPECT_NEAR(precomputed.kd, tuned.kd, 1e-9 * tuned.kd) << name;
    EXPECT_EQ(precomputed.derivative_filter_tf_s, tuned.derivative_filter_tf_s) << name;
    EXPECT_EQ(precomputed.u_max_mm_s, 123.0);
    EXPECT_TRUE(precomputed.feedforward);
#endif
  }
}

// Linearised DVSC+DDC closed-loop poles: r = q - eta/phi (S1 eq. (14)),
// 1 - g (eq. (9)), the sliding-surface zero of G(zI-A)^-1 B, and 0 (the
// recursive surface adds no dynamics of its own), whatever gamma is.
TEST(PidTuning, LinearisedSlidingModeClosedLoopPolesAreTheDecoupledOnes) {
  for (hal::Axis axis : {hal::Axis::x, hal::Axis::y}) {
    for (ControllerKind kind : {ControllerKind::dvsc, ControllerKind::rdvsc}) {
      const AxisModel m = paper_axis_model(axis);
      const SlidingModeParams p = paper_sliding_mode_params(axis, kind);
      const double gb = p.G_position_1_s * m.B(0) + p.G_speed * m.B(1);
      const double z0 = (p.G_position_1_s * (m.A(1, 1) * m.B(0) - m.A(0, 1) * m.B(1)) + p.G_speed * m.B(1)) / gb;
      std::vector<double> expected = {p.q - p.eta_mm_s / p.phi_mm_s, 1.0 - p.g, z0, 0.0, 0.0};
      std::vector<double> got;
      for (const auto& pole : closed_loop_poles(m, linearised_sliding_mode(m, p))) {
        EXPECT_NEAR(pole.imag(), 0.0, 1e-6);
        got.push_back(pole.real());
      }
      std::sort(expected.begin(), expected.end());
      std::sort(got.begin(), got.end());
      for (std::size_t i = 0; i < got.size(); ++i)
        EXPECT_NEAR(got[i], expected[i], 1e-6) << hal::axis_name(axis) << " " << to_string(kind) << " pole " << i;
    }
  }
}

TEST(PidTuning, UnreachablePhaseMarginWithADerivativeFilterIsReportedNotHidden) {
  PidTuningOptions o;
  o.derivative_filter_n = 10.0;  // tf = Td/10: at most ~55 deg at the X crossover
  const PidTuningReport r =
      tune_pid_equal_crossover(paper_axis_model(hal::Axis::x), paper_dvsc_params(hal::Axis::x), o);
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(r.phase_margin_reached);
  EXPECT_LT(r.pid_phase_margin_deg, 60.0);
  EXPECT_GT(r.pid_phase_margin_deg, 45.0);
  EXPECT_TRUE(r.pid_closed_loop_stable);
  EXPECT_NEAR(r.pid_crossover_rad_s / r.dvsc_crossover_rad_s, 1.0, 0.01);
}

TEST(PidTuning, LowerCapIsMatchedAndUncappedMarginIsMatchedExactly) {
  const AxisModel m = paper_axis_model(hal::Axis::y);
  PidTuningOptions o;
  o.max_phase_margin_deg = 45.0;
  PidTuningReport r = tune_pid_equal_crossover(m, paper_dvsc_params(hal::Axis::y), o);
  ASSERT_TRUE(r.ok) << r.note;
  EXPECT_NEAR(r.pid_phase_margin_deg, 45.0, 0.1);
  o.max_phase_margin_deg = 80.0;  // above the DVSC+DDC margin: match it
  r = tune_pid_equal_crossover(m, paper_dvsc_params(hal::Axis::y), o);
  ASSERT_TRUE(r.ok) << r.note;
  EXPECT_FALSE(r.phase_margin_capped);
  EXPECT_NEAR(r.pid_phase_margin_deg, r.dvsc_phase_margin_deg, 0.1);
}

TEST(PidTuning, InvalidSlidingModeParametersGiveNoGains) {
  SlidingModeParams p = paper_dvsc_params(hal::Axis::x);
  p.g = 1.5;
  const PidTuningReport r = tune_pid_equal_crossover(paper_axis_model(hal::Axis::x), p);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.kp, 0.0);
}

}  // namespace
}  // namespace tnv::fw
