// Closed-loop properties of DVSC+DDC / R-DVSC+DDC on the nominal plant
// x_{k+1} = A x_k + B u_k + B d_k (S1 eq. (3)) with the paper's model and
// Tables 1/2 parameters.
#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "firmware/control/rdvsc_controller.hpp"
#include "firmware/control/unit_saturation.hpp"
#include "tests/firmware/control/nominal_plant.hpp"
#include "tests/firmware/test_units.hpp"

namespace tnv::fw {
namespace {

using test::NominalPlant;

using test_units::kPeriodS;
using test_units::kPi;

struct Case {
  hal::Axis axis;
  ControllerKind kind;
};
constexpr Case kCases[] = {{hal::Axis::x, ControllerKind::dvsc},
                           {hal::Axis::x, ControllerKind::rdvsc},
                           {hal::Axis::y, ControllerKind::dvsc},
                           {hal::Axis::y, ControllerKind::rdvsc}};

std::string label(const Case& c) { return std::string(1, hal::axis_name(c.axis)) + " " + to_string(c.kind); }

double gb_of(const SlidingModeParams& p, const AxisModel& m) { return p.G_position_1_s * m.B(0) + p.G_speed * m.B(1); }

// One closed-loop run; records s_k, d^_k, d_k, u_k, G e_k.
struct Trace {
  std::vector<double> s, d_hat, d, u, ge, position_error_mm;
  std::vector<bool> saturated;
};

template <class Disturbance, class RefPos, class RefSpeed>
Trace run(const Case& c, const SlidingModeParams& p, int ticks, Eigen::Vector2d x0, Disturbance disturbance,
          RefPos ref_pos, RefSpeed ref_speed) {
  const AxisModel model = paper_axis_model(c.axis);
  RdvscController ctl(c.kind, model, p);
  EXPECT_TRUE(ctl.configured()) << ctl.config_status().field << " " << ctl.config_status().reason;
  NominalPlant plant{model, x0};
  Trace tr;
  for (int k = 0; k < ticks; ++k) {
    const AxisReference ref = test::reference_at(k, kPeriodS, ref_pos, ref_speed);
    const double u = ctl.update(plant.state(), ref);
    const ControllerSignals sig = ctl.signals();
    const double d = disturbance(k);
    tr.s.push_back(sig.s);
    tr.d_hat.push_back(sig.d_hat_mm_s);
    tr.d.push_back(d);
    tr.u.push_back(u);
    tr.saturated.push_back(sig.saturated);
    tr.ge.push_back(p.G_position_1_s * (plant.x(0) - ref.position_mm) + p.G_speed * (plant.x(1) - ref.speed_mm_s));
    tr.position_error_mm.push_back(ref.position_mm - plant.x(0));
    plant.step(u, d);
  }
  return tr;
}

SlidingModeParams unclamped(SlidingModeParams p) {
  p.u_max_mm_s = 1e9;  // (8) is an identity of the unclamped law
  return p;
}

TEST(RdvscClosedLoop, Eq8AndEq9HoldEveryTickInsideAndOutsideTheBoundaryLayer) {
  for (const Case& c : kCases) {
    const SlidingModeParams p = unclamped(paper_sliding_mode_params(c.axis, c.kind));
    const AxisModel model = paper_axis_model(c.axis);
    const double gb = gb_of(p, model);
    const int ticks = 4000;
    // Arbitrary disturbance: steps (one large enough to leave the layer),
    // a 40 Hz sinusoid and uniform noise, in mm/s.
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> noise(-0.5, 0.5);
    std::vector<double> dist(ticks + 1);
    for (int k = 0; k <= ticks; ++k) {
      const double t = k * kPeriodS;
      dist[k] = (k >= 500 ? 3.0 : 0.0) + (k >= 2000 ? 60.0 : 0.0) + (k >= 3000 ? -45.0 : 0.0) +
                1.5 * std::sin(2 * kPi * 40.0 * t + 0.3) + noise(rng);
    }
    // Circle-like reference (6 mm, 2 mm/s) and a 0.2 mm initial error.
    const double w = 2.0 / 6.0;
    auto pos = [&](double t) { return 6.0 * std::cos(w * t); };
    auto spd = [&](double t) { return -6.0 * w * std::sin(w * t); };
    const Eigen::Vector2d x0(6.0 + 0.2, 0.0);
    const Trace tr = run(c, p, ticks, x0, [&](int k) { return dist[k]; }, pos, spd);

    int outside = 0, outside_late = 0;
    double worst8 = 0.0, worst9 = 0.0;
    for (int k = 0; k + 1 < ticks; ++k) {
      const double s = tr.s[k];
      if (std::fabs(s) > p.phi_mm_s) {
        ++outside;
        if (k > 1000) ++outside_late;
      }
      // S1 eq. (8)
      const double d_tilde = tr.d[k] - tr.d_hat[k];
      const double s_next_pred = p.q * s - p.eta_mm_s * sat_unit(s / p.phi_mm_s) + gb * d_tilde;
      const double err8 = std::fabs(tr.s[k + 1] - s_next_pred);
      worst8 = std::max(worst8, err8 / std::max(1.0, std::fabs(s)));
      ASSERT_LE(err8, 1e-9 * std::max(1.0, std::fabs(s)))
          << label(c) << ": eq. (8) violated at tick " << k << " by " << err8 << " mm/s (s_k = " << s << " mm/s)";
      // S1 eq. (9)
      const double d_tilde_next = tr.d[k + 1] - tr.d_hat[k + 1];
      const double pred9 = tr.d[k + 1] - tr.d[k] + (1.0 - p.g) * d_tilde;
      const double err9 = std::fabs(d_tilde_next - pred9);
      worst9 = std::max(worst9, err9);
      ASSERT_LE(err9, 1e-9 * std::max(1.0, std::fabs(tr.d[k])))
          << label(c) << ": eq. (9) violated at tick " << k << " by " << err9 << " mm/s";
    }
    EXPECT_GT(outside, 3) << label(c) << ": the run must include ticks with |s| > phi";
    EXPECT_GT(outside_late, 0) << label(c) << ": the 60 mm/s disturbance step must push s out of the layer";
    for (bool sat : tr.saturated) ASSERT_FALSE(sat) << label(c) << ": the clamp must stay inactive for this test";
  }
}

TEST(RdvscClosedLoop, DdcConvergesToAConstantDisturbanceAndTheTrackingErrorVanishes) {
  for (const Case& c : kCases) {
    const SlidingModeParams p = paper_sliding_mode_params(c.axis, c.kind);
    const double d_mm_s = 3.0;
    // Ramp at 2 mm/s: exactly feasible for the paper model (A12 + B1 = T, 1 - A22 = B2).
    auto pos = [](double t) { return 2.0 * t; };
    auto spd = [](double) { return 2.0; };
    const int ticks = 2000;
    const Trace tr = run(c, p, ticks, Eigen::Vector2d(0.0, 2.0), [&](int) { return d_mm_s; }, pos, spd);
    // d~_k = (1 - g)^k d~_1 after the first tick: 300 ticks is < 1e-15 of the start.
    for (int k = 300; k < ticks; ++k)
      ASSERT_NEAR(tr.d_hat[k], d_mm_s, 1e-6) << label(c) << ": d^ at tick " << k << " is " << tr.d_hat[k]
                                             << " mm/s, disturbance " << d_mm_s << " mm/s";
    for (int k = 1500; k < ticks; ++k)
      ASSERT_LT(std::fabs(tr.position_error_mm[k]), 1e-6)
          << label(c) << ": position error " << tr.position_error_mm[k] * 1e3 << " um at tick " << k;
    // The disturbance did act: the transient error was visible.
    double peak_um = 0.0;
    for (double e : tr.position_error_mm) peak_um = std::max(peak_um, std::fabs(e) * 1e3);
    EXPECT_GT(peak_um, 0.01) << label(c);
  }
}

// With the clamp active the DDC is fed the applied command, so eq. (9) still
// holds and eq. (8) gains exactly the unapplied part GB (u_applied - u_law).
TEST(RdvscClosedLoop, Eq9StillHoldsWhileTheCommandIsClamped) {
  for (const Case& c : kCases) {
    const SlidingModeParams p = paper_sliding_mode_params(c.axis, c.kind);
    const AxisModel model = paper_axis_model(c.axis);
    const double gb = gb_of(p, model);
    RdvscController ctl(c.kind, model, p);
    NominalPlant plant{model, Eigen::Vector2d::Zero()};
    auto dist = [](int k) { return 2.0 + 1.0 * std::sin(2 * kPi * 30.0 * k * kPeriodS) + (k >= 600 ? -300.0 : 0.0); };
    double s_prev = 0.0, d_tilde_prev = 0.0, u_gap_prev = 0.0;
    int clamped = 0;
    for (int k = 0; k < 1500; ++k) {
      const double u = ctl.update(plant.state(), test::resting_reference(20.0));  // 20 mm step: saturates
      const ControllerSignals sig = ctl.signals();
      const double d_tilde = dist(k) - sig.d_hat_mm_s;
      if (k > 0) {
        const double s_pred = p.q * s_prev - p.eta_mm_s * sat_unit(s_prev / p.phi_mm_s) + gb * (d_tilde_prev + u_gap_prev);
        ASSERT_NEAR(sig.s, s_pred, 1e-9 * std::max(1.0, std::fabs(s_prev))) << label(c) << " tick " << k;
        const double pred9 = dist(k) - dist(k - 1) + (1.0 - p.g) * d_tilde_prev;
        ASSERT_NEAR(d_tilde, pred9, 1e-9 * std::max(1.0, std::fabs(dist(k))))
            << label(c) << ": eq. (9) broken under clamping at tick " << k;
      }
      if (sig.saturated) ++clamped;
      s_prev = sig.s;
      d_tilde_prev = d_tilde;
      u_gap_prev = u - ctl.u_law_mm_s();
      plant.step(u, dist(k));
    }
    EXPECT_GT(clamped, 20) << label(c) << ": the run must clamp";
  }
}

TEST(RdvscClosedLoop, Theorem2SlidingVariableEntersAndStaysInsideTheUltimateBound) {
  for (const Case& c : kCases) {
    const SlidingModeParams p = unclamped(paper_sliding_mode_params(c.axis, c.kind));
    const AxisModel model = paper_axis_model(c.axis);
    const double gb = gb_of(p, model);
    const double bound = p.eta_mm_s / (1.0 - p.q + p.eta_mm_s / p.phi_mm_s);
    ASSERT_LT(bound, p.phi_mm_s) << label(c);
    // Slowly varying disturbance (2 Hz, 0.5 mm/s, offset 0.3 mm/s): |GB d~| stays
    // well below eta, the theorem's assumption. Initial error 50 um, s_0 >> phi.
    auto dist = [](int k) { return 0.3 + 0.5 * std::sin(2 * kPi * 2.0 * k * kPeriodS); };
    auto pos = [](double) { return 1.0; };
    auto spd = [](double) { return 0.0; };
    const int ticks = 3000;
    const Trace tr = run(c, p, ticks, Eigen::Vector2d(1.05, 0.0), dist, pos, spd);
    ASSERT_GT(std::fabs(tr.s[0]), p.phi_mm_s) << label(c) << ": must start outside the layer";
    for (int k = 0; k < ticks; ++k)
      ASSERT_LT(std::fabs(gb * (tr.d[k] - tr.d_hat[k])), p.eta_mm_s)
          << label(c) << ": theorem assumption eta > |GB d~| broken at tick " << k;
    bool entered = false;
    int k_enter = -1;
    for (int k = 0; k + 1 < ticks; ++k) {
      if (!entered && std::fabs(tr.s[k]) > p.phi_mm_s) {
        ASSERT_LT(std::fabs(tr.s[k + 1]), std::fabs(tr.s[k]))
            << label(c) << ": |s| must decrease outside the layer (tick " << k << ", s = " << tr.s[k] << " mm/s)";
      } else if (!entered) {
        entered = true;
        k_enter = k;
      }
      if (entered) {
        ASSERT_LE(std::fabs(tr.s[k]), p.phi_mm_s)
            << label(c) << ": s left the boundary layer at tick " << k << ": " << tr.s[k] << " mm/s";
      }
    }
    ASSERT_TRUE(entered) << label(c);
    EXPECT_LT(k_enter, 100) << label(c) << ": reaching took " << k_enter << " ms";
    for (int k = k_enter + 200; k < ticks; ++k)
      ASSERT_LT(std::fabs(tr.s[k]), bound)
          << label(c) << ": |s| = " << std::fabs(tr.s[k]) << " mm/s exceeds eta/(1-q+eta/phi) = " << bound
          << " mm/s at tick " << k;
  }
}

// Remark 2 / Theorem 5 (with the digest's [fix]: eta/phi in (28)-(29)).
// In the layer, G e = GB (1 - gamma z^-1)(z - 1) / ((z - r)(z - 1 + g)) d, so a
// sinusoid at w is attenuated by |1 - gamma e^{-jwT}| relative to DVSC+DDC:
// below cos(wT) = gamma/2, i.e. 217 Hz (X) / 226 Hz (Y), R-DVSC+DDC is better.
TEST(RdvscClosedLoop, Remark2RdvscHasTheSmallerUltimateSurfaceErrorForCuttingFrequencies) {
  for (hal::Axis axis : {hal::Axis::x, hal::Axis::y}) {
    for (double f_hz : {30.0, 40.0, 50.0}) {
      const double amp = 1.0;  // mm/s
      auto dist = [&](int k) { return amp * std::sin(2 * kPi * f_hz * k * kPeriodS); };
      auto pos = [](double) { return 0.0; };
      auto spd = [](double) { return 0.0; };
      double peak[2] = {0.0, 0.0};
      double bound[2] = {0.0, 0.0};
      const ControllerKind kinds[2] = {ControllerKind::dvsc, ControllerKind::rdvsc};
      for (int i = 0; i < 2; ++i) {
        const Case c{axis, kinds[i]};
        const SlidingModeParams p = paper_sliding_mode_params(axis, kinds[i]);
        const double gb = gb_of(p, paper_axis_model(axis));
        const int ticks = 3000;
        const Trace tr = run(c, p, ticks, Eigen::Vector2d::Zero(), dist, pos, spd);
        double m = 0.0;
        for (int k = 0; k + 1 < ticks; ++k) m = std::max(m, std::fabs(tr.d[k + 1] - tr.d[k]));
        bound[i] = (1.0 - p.gamma) * gb * m / ((1.0 - p.q + p.eta_mm_s / p.phi_mm_s) * p.g);  // (28)/(29)
        for (int k = 2000; k < ticks; ++k) {
          ASSERT_LT(std::fabs(tr.s[k]), p.phi_mm_s) << label(c) << ": left the layer";
          peak[i] = std::max(peak[i], std::fabs(tr.ge[k]));
        }
        EXPECT_LT(peak[i], bound[i]) << label(c) << " " << f_hz << " Hz: |G e| " << peak[i] << " mm/s above bound "
                                     << bound[i] << " mm/s";
      }
      const double gamma = paper_rdvsc_params(axis).gamma;
      const double predicted = std::abs(1.0 - gamma * std::polar(1.0, -2 * kPi * f_hz * kPeriodS));
      EXPECT_LT(peak[1], peak[0]) << hal::axis_name(axis) << " " << f_hz << " Hz: R-DVSC |G e| " << peak[1]
                                  << " mm/s, DVSC " << peak[0] << " mm/s";
      EXPECT_NEAR(peak[1] / peak[0], predicted, 0.02)
          << hal::axis_name(axis) << " " << f_hz << " Hz: ratio of ultimate |G e| R-DVSC/DVSC";
    }
  }
}

}  // namespace
}  // namespace tnv::fw
