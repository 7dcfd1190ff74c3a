#pragma once
// S3 reproduction: an ARSC variant against the paper's end-milling process
// (emu::MillingProcess, eqs. (27)-(28)) at the paper's T = 0.15 s, depth
// 0.2 -> 1.0 -> 0.2 mm over 30 s (Fig. 4), force reference f* = 1
// (normalised). The control computed at sample t is applied from t+1.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "emulator/milling_process.hpp"
#include "emulator/scenario.hpp"
#include "firmware/adaptive/arsc/arsc_gains.hpp"
#include "firmware/adaptive/arsc/arv2_rls.hpp"
#include "firmware/adaptive/arsc/cutting_gain_rls.hpp"
#include "firmware/adaptive/arsc/gain_guard.hpp"
#include "firmware/adaptive/arsc/pole_sets.hpp"
#include "tools/hil/arsc_test_stage.hpp"

namespace tnv::hil {

// The force reference f* = 1 of the normalised study is the S3 experiment's
// peak-force reference, 150 N (seed digest S3; the tick study's f*).
inline constexpr double kS3ForceReferenceN = 150.0;

// Gaussian noise on the force the loop (and its test stage) reads,
// normalised (f* = 1); seeded. 0: the paper's noiseless measurement.
struct ArscForceNoise {
  double rms = 0.0;
  std::uint64_t seed = 0;
};

// A scenario's force ADC noise in the study's units. The emulator's force
// sensor puts force_n * [force_sensor] volts_per_n on the ADC's input and
// adds [noise] force_adc_v_rms there (emulator/machine.cpp,
// Machine::Impl::tick_samples; docs/scenarios.md): the noise is
// force_adc_v_rms / volts_per_n newtons, and f* = 1 is kS3ForceReferenceN.
// The bench: 0.004 V / (1/30 V/N) = 0.12 N = 8.0e-4 of f*. Seeded from
// [noise] seed. Empty error, or why the scenario cannot be used (a sensor
// with volts_per_n = 0 under noise reads nothing but noise).
struct ArscScenarioNoise {
  ArscForceNoise noise{};
  std::string error;
};
ArscScenarioNoise arsc_force_noise(const emu::Scenario& scenario);

enum class ArscVariant : std::uint8_t { faithful, robust };
constexpr const char* to_string(ArscVariant v) noexcept { return v == ArscVariant::faithful ? "faithful" : "robust"; }

struct ArscRunConfig {
  fw::arsc::PoleSet poles = fw::arsc::PoleSet::case1;
  ArscVariant variant = ArscVariant::robust;
  emu::MillingProcessParams process{};
  emu::DepthProfile depth{};  // S3 Fig. 4: 0.2 -> 1.0 mm over 15 s, back over 15 s
  double duration_s = 30.0;
  double force_ref = 1.0;
  double settle_s = 3.0;           // the force error is scored after this
  double divergence_limit = 100.0; // |f|, |v| or |u| above this (normalised): diverged, run stops
  fw::arsc::Arv2RlsParams faithful_rls{};  // the paper gives no lambda or P0
  double robust_forgetting = 0.05;
  double robust_initial_covariance = 10.0;
  std::size_t test_stage_samples = 100;  // robust: open-loop samples at the start depth
  ArscForceNoise force_noise{};          // on the force the loop and the test stage read
  // Robust: alpha of the gain design's tracker (fw::arsc::GainTrendParams); 0 = automatic:
  // 1 (off) on a noiseless force, kNoisyGainTrendAlpha on a noisy one.
  double robust_gain_trend_alpha = 0.0;
};

// The tracker's alpha with a noisy force: from a sweep of 0.25 ... 0.5 over
// 32 noise seeds at 0, 1 and 2 times the bench's noise (docs/robustness.md).
inline constexpr double kNoisyGainTrendAlpha = 0.35;
double robust_gain_trend_alpha(const ArscRunConfig& config) noexcept;

struct ArscTracePoint {
  double t_s = 0.0;
  double depth_mm = 0.0;
  double force = 0.0;  // f(t), the process' (what is scored)
  double force_measured = 0.0;  // f(t) as the loop read it (with force_noise)
  double feed = 0.0;   // v(t)
  double u = 0.0;      // applied over [t, t+1)
  fw::arsc::ArscGains gains{};  // after this sample's update
  bool have_gains = false;
  fw::arsc::GuardReason reason = fw::arsc::GuardReason::none;
  std::array<double, 10> theta{};  // faithful: theta1 (5), theta2 (5) of S3 eq. (5)
  double cutting_gain = 0.0;       // robust: g^; faithful: -phi112^ (the same quantity in eq. (1))
  double true_cutting_gain = 0.0;  // b21 delta(t)
};

struct ArscRunResult {
  ArscRunConfig config{};
  std::vector<ArscTracePoint> trace;
  double force_error_max_pct = 0.0;  // after settle_s, % of f*
  double force_error_rms_pct = 0.0;
  std::size_t samples_over_10pct = 0;
  std::size_t scored_samples = 0;
  bool diverged = false;
  std::optional<double> diverged_at_s;
  std::optional<double> first_gains_s;
  std::array<std::uint32_t, fw::arsc::kGuardReasonCount> reason_counts{};
  std::optional<TestStageFit> test_stage;  // robust only
  emu::MillingCoefficients process_coefficients{};
};

ArscRunResult run_arsc(const ArscRunConfig& config);

// run_arsc over noise seeds force_noise.seed + 0 .. seeds - 1: the worst
// peak error, the mean rms, the runs that diverged; `first` is seed + 0's.
struct ArscSeedSweep {
  ArscRunResult first;
  int seeds = 0;
  double force_error_max_pct_worst = 0.0;
  double force_error_rms_pct_mean = 0.0;
  int diverged_runs = 0;
};
ArscSeedSweep run_arsc_seeds(const ArscRunConfig& config, int seeds);

}  // namespace tnv::hil
