// The planner's learned state: exported and restored, a planner continues
// bit for bit; every state the planner can reach passes validate(), and a
// damaged one is refused whole.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "firmware/adaptive/boring/boring_infeed_planner.hpp"

namespace tnv::fw {
namespace {

// d = C S^alpha L^beta of S4's first set, with a seeded gauge error.
struct StateProcess {
  double c_mm = 0.0871, alpha = 0.5025, beta = 0.2676;
  std::uint64_t lcg = 12345;
  double noise_mm(double sigma_mm) {  // uniform, zero mean, sigma_mm standard deviation
    lcg = lcg * 6364136223846793005ull + 1442695040888963407ull;
    const double u = static_cast<double>(lcg >> 11) / 9007199254740992.0;
    return (u - 0.5) * std::sqrt(12.0) * sigma_mm;
  }
};

constexpr double kStateL[2] = {40.0, 310.0};

// One part: infeeds from the planner, the process deflects, the gauge reads; returns the report.
BoringPartReport bore_one_part(BoringInfeedPlanner& planner, StateProcess& process, double sigma_mm,
                               double (&infeeds)[2]) {
  const BoringPlannerParams& p = planner.params();
  BoreMeasurement m[2];
  for (int i = 0; i < 2; ++i) {
    infeeds[i] = planner.infeed(kStateL[i]).infeed_mm_rev;
    const double d = process.c_mm * std::pow(infeeds[i], process.alpha) * std::pow(kStateL[i], process.beta) +
                     process.noise_mm(sigma_mm);
    m[i] = {kStateL[i], infeeds[i], bore_error_from_deflection_mm(d, p.target_deflection_mm, p.force_angle_deg)};
  }
  return planner.record_part(m);
}

BoringPlannerParams state_params(BoringGainForm form, BoringResetCount count, int reset_after) {
  BoringPlannerParams p;
  p.gain_form = form;
  p.reset_count = count;
  p.reset_after = reset_after;
  return p;
}

TEST(BoringPlannerState, ARestoredPlannerContinuesBitForBitForEveryGainFormAndCountingRule) {
  for (BoringGainForm form : {BoringGainForm::normalised, BoringGainForm::kalman, BoringGainForm::printed})
    for (BoringResetCount count : {BoringResetCount::measurements, BoringResetCount::parts, BoringResetCount::positions}) {
      const BoringPlannerParams p = state_params(form, count, 2);
      BoringInfeedPlanner running(p);
      StateProcess process;
      double infeeds[2];
      for (int part = 1; part <= 12; ++part) ASSERT_TRUE(bore_one_part(running, process, 0.03, infeeds).check.ok);
      // The process changes, so the continuation goes through resets too.
      process.c_mm = 0.15;
      process.alpha = 0.7;
      process.beta = 0.4;
      BoringInfeedPlanner restored(p);
      ASSERT_TRUE(restored.restore(running.state()).ok);
      EXPECT_TRUE(restored.state() == running.state());
      StateProcess twin = process;
      const int resets_before = running.resets();
      for (int part = 13; part <= 40; ++part) {
        double a[2];
        double b[2];
        const BoringPartReport ra = bore_one_part(running, process, 0.03, a);
        const BoringPartReport rb = bore_one_part(restored, twin, 0.03, b);
        ASSERT_TRUE(ra.check.ok && rb.check.ok);
        EXPECT_EQ(a[0], b[0]) << to_string(form) << "/" << to_string(count) << " part " << part;
        EXPECT_EQ(a[1], b[1]) << to_string(form) << "/" << to_string(count) << " part " << part;
        EXPECT_EQ(ra.reset, rb.reset);
      }
      EXPECT_TRUE(restored.state() == running.state());
      EXPECT_GT(running.resets(), resets_before) << to_string(form) << "/" << to_string(count)
                                                 << ": the change was seen (the runs were restored too)";
    }
}

TEST(BoringPlannerState, EveryStateOfALongNoisyRunIsPlausible) {
  for (BoringGainForm form : {BoringGainForm::normalised, BoringGainForm::kalman, BoringGainForm::printed}) {
    BoringInfeedPlanner planner(state_params(form, BoringResetCount::measurements, 1));
    StateProcess process;
    double infeeds[2];
    ASSERT_TRUE(validate(planner.state(), 1.0).ok) << "fresh";
    for (int part = 1; part <= 3000; ++part) {
      if (part == 1500) process.c_mm = 0.05;
      ASSERT_TRUE(bore_one_part(planner, process, 0.016231, infeeds).check.ok);
      const ParamCheck c = validate(planner.state(), 1.0);
      ASSERT_TRUE(c.ok) << to_string(form) << " part " << part << ": " << c.field << ": " << c.reason;
    }
    EXPECT_GT(planner.resets(), 0) << "reset_after 1: the run went through resets";
  }
}

// A started planner's state to damage.
BoringPlannerState learned_state() {
  BoringInfeedPlanner planner;
  StateProcess process;
  double infeeds[2];
  for (int part = 1; part <= 5; ++part) bore_one_part(planner, process, 0.016231, infeeds);
  return planner.state();
}

TEST(BoringPlannerState, ADamagedStateIsRefusedAndTheNamedFieldIsTheDamagedOne) {
  const BoringPlannerState good = learned_state();
  ASSERT_TRUE(validate(good, 1.0).ok);
  struct Damage {
    const char* field;
    void (*apply)(BoringPlannerState&);
  };
  const Damage damages[] = {
      {"started", [](BoringPlannerState& s) { s.started = false; }},
      {"parts", [](BoringPlannerState& s) { s.parts = 0; }},
      {"parts", [](BoringPlannerState& s) { s.parts = -3; }},
      {"parts", [](BoringPlannerState& s) { s.parts = kMaxBoringParts + 1; }},
      {"resets", [](BoringPlannerState& s) { s.resets = -1; }},
      {"resets", [](BoringPlannerState& s) { s.resets = s.parts * 9 + 1; }},
      {"streak", [](BoringPlannerState& s) { s.streak = 101; }},
      {"position_streak", [](BoringPlannerState& s) { s.position_streak[5] = -1; }},
      {"theta", [](BoringPlannerState& s) { s.theta(1) = std::numeric_limits<double>::quiet_NaN(); }},
      {"theta", [](BoringPlannerState& s) { s.theta(0) = 2e6; }},
      {"innovation", [](BoringPlannerState& s) { s.innovation = std::numeric_limits<double>::infinity(); }},
      {"covariance", [](BoringPlannerState& s) { s.covariance(0, 1) += 1e-9; }},
      {"covariance", [](BoringPlannerState& s) { s.covariance(2, 2) = 1.5; }},
      {"covariance", [](BoringPlannerState& s) { s.covariance(1, 1) = -1e-3; }},
      {"covariance", [](BoringPlannerState& s) {
         s.covariance(0, 2) = s.covariance(2, 0) = 2.0 * std::sqrt(s.covariance(0, 0) * s.covariance(2, 2));
       }},
  };
  for (const Damage& d : damages) {
    BoringPlannerState bad = good;
    d.apply(bad);
    const ParamCheck c = validate(bad, 1.0);
    EXPECT_FALSE(c.ok) << d.field;
    EXPECT_STREQ(c.field, d.field) << c.reason;
    // restore() takes it whole or not at all.
    BoringInfeedPlanner planner;
    const BoringPlannerState before = planner.state();
    EXPECT_FALSE(planner.restore(bad).ok) << d.field;
    EXPECT_TRUE(planner.state() == before) << d.field << ": a refused restore changed the planner";
  }
}

TEST(BoringPlannerState, APlannerThatHasNotStartedHasLearnedNothing) {
  BoringPlannerState fresh = fresh_boring_state(1.0);
  EXPECT_TRUE(validate(fresh, 1.0).ok);
  EXPECT_TRUE(BoringInfeedPlanner().state() == fresh);
  fresh.theta(2) = 0.3;  // an estimate without a start-up part
  EXPECT_FALSE(validate(fresh, 1.0).ok);
  EXPECT_FALSE(validate(fresh_boring_state(1.0), 0.5).ok) << "P0 = I is not P0 = 0.5 I";
}

}  // namespace
}  // namespace tnv::fw
