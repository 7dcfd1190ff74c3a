// tnv-hil arsc design | run | compare | tick: S3 adaptive cutting-force
// regulation (ARSC), the paper's loop and the robust variant.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "firmware/adaptive/arsc/closed_loop_matrix.hpp"
#include "firmware/adaptive/arsc/faithful_gain_solve.hpp"
#include "firmware/control/matrix_poles.hpp"
#include "tools/cli/output_path.hpp"
#include "tools/hil/arsc_run.hpp"
#include "tools/hil/arsc_tick_json.hpp"
#include "tools/hil/arsc_tick_study.hpp"
#include "tools/hil/plot_data.hpp"
#include "tools/hil/seeded_scenario.hpp"
#include "tools/tnv-hil/cli_support.hpp"
#include "tools/tnv-hil/commands.hpp"

namespace tnv::cli {

namespace {

using namespace fw::arsc;
using nlohmann::json;

json design_gains_json(const ArscGains& g) {
  return {{"gamma01", g.gamma01}, {"k", g.k},           {"gamma11", g.gamma11}, {"gamma13", g.gamma13},
          {"gamma22", g.gamma22}, {"gamma31", g.gamma31}, {"gamma32", g.gamma32}};
}

json all_gains_json(const ArscGains& g) {
  json j = design_gains_json(g);
  j["gamma02"] = g.gamma02;
  j["gamma03"] = g.gamma03;
  j["gamma12"] = g.gamma12;
  j["gamma21"] = g.gamma21;
  j["gamma41"] = g.gamma41;
  j["gamma42"] = g.gamma42;
  return j;
}

struct ArscDesignOptions {
  std::string poles = "case1";
  bool json = false;
};

int run_arsc_design(const ArscDesignOptions& o) {
  const PoleSet set = *parse_pole_set(o.poles);
  const Arv2Model model = paper_initial_model();
  const std::array<double, 7> d_star = desired_coefficients(paper_poles(set));
  const FixedGains fixed{};
  const GainDesign d = solve_faithful_gains(model, d_star, fixed, GuardLimits{});
  const Fig3System sys = fig3_system(model, d_star, fixed);
  const std::string status = d.reason == GuardReason::none              ? "ok"
                             : d.reason == GuardReason::ill_conditioned ? "singular"
                                                                        : "refused";
  json j = {{"pole_set", o.poles},
            {"status", status},
            {"reason", to_string(d.reason)},
            {"gamma01_eq25", sys.gamma01},
            {"rcond", d.rcond},
            {"requested_coefficients", d_star},
            {"model", "paper starting estimates, S3 eq. (29)"},
            {"timing", "control computed at t applied from t+1 (Fig. 2 exact)"}};
  if (d.reason == GuardReason::none) {
    j["gains"] = design_gains_json(d.gains);
    const Matrix7 a = closed_loop_matrix(model, d.gains);
    const auto achieved = characteristic_coefficients<7>(a);
    double worst = 0.0;
    for (std::size_t i = 0; i < 7; ++i) worst = std::max(worst, std::fabs(achieved[i] - d_star[i]));
    j["achieved_coefficients"] = achieved;
    j["max_coefficient_error"] = worst;
    json poles = json::array();
    for (const std::complex<double>& z : fw::matrix_poles<7>(a)) poles.push_back({z.real(), z.imag()});
    j["closed_loop_poles"] = poles;
  } else {
    j["gains"] = nullptr;
  }
  if (o.json) {
    std::cout << j.dump(2) << '\n';
    return kExitOk;
  }
  std::printf("S3 ARSC design, %s, at the paper's starting estimates (eq. 29), fixed gains (eq. 32)\n", o.poles.c_str());
  std::printf("  gamma01 (eq. 25) = %.6f\n", sys.gamma01);
  if (d.reason == GuardReason::none) {
    const ArscGains& g = d.gains;
    std::printf("  k = %.6f  gamma11 = %.6f  gamma13 = %.6f  gamma22 = %.6f  gamma31 = %.6f  gamma32 = %.6f\n", g.k,
                g.gamma11, g.gamma13, g.gamma22, g.gamma31, g.gamma32);
    std::printf("  (26) rcond %.3g; 7x7 closed-loop coefficients match the requested ones to %.2g\n", d.rcond,
                j["max_coefficient_error"].get<double>());
  } else if (d.reason == GuardReason::ill_conditioned) {
    std::printf("  singular: (26) has rcond %.3g (gamma01 = 1 or gamma03 + gamma41 gamma02 / gamma42 = %.3g makes it "
                "singular for every model)\n",
                d.rcond, fixed.gamma03 + fixed.gamma41 * fixed.gamma02 / fixed.gamma42);
  } else {
    std::printf("  refused: %s\n", to_string(d.reason));
  }
  return kExitOk;
}

struct RunOptions {
  std::string poles = "case1";
  std::string variant = "robust";
  bool json = false;
  std::string plot;
  double forgetting = -1.0;  // variant's default
  double p0 = -1.0;
  std::string scenario;      // empty: the paper's noiseless measurement
  double trend_alpha = 0.0;  // robust: 0 = automatic
};

// --scenario: the scenario's force ADC noise on the force the S3 loop reads
// (hil::arsc_force_noise); nullopt after a one-line message.
std::optional<hil::ArscForceNoise> force_noise_or_report(const std::string& name_or_file) {
  if (name_or_file.empty()) return hil::ArscForceNoise{};
  const auto scenario = resolve_scenario_or_report(name_or_file);
  if (!scenario) return std::nullopt;
  const hil::ArscScenarioNoise n = hil::arsc_force_noise(*scenario);
  if (!n.error.empty()) {
    std::fprintf(stderr, "tnv-hil: --scenario %s: %s\n", name_or_file.c_str(), n.error.c_str());
    return std::nullopt;
  }
  return n.noise;
}

hil::ArscRunConfig run_config(const std::string& poles, const std::string& variant, double forgetting, double p0) {
  hil::ArscRunConfig c;
  c.poles = *parse_pole_set(poles);
  c.variant = variant == "faithful" ? hil::ArscVariant::faithful : hil::ArscVariant::robust;
  if (c.variant == hil::ArscVariant::faithful) {
    if (forgetting > 0.0) c.faithful_rls.forgetting = forgetting;
    if (p0 > 0.0) c.faithful_rls.initial_covariance = p0;
  } else {
    if (forgetting > 0.0) c.robust_forgetting = forgetting;
    if (p0 > 0.0) c.robust_initial_covariance = p0;
  }
  return c;
}

json reasons_json(const std::array<std::uint32_t, kGuardReasonCount>& counts) {
  json j = json::object();
  for (int i = 0; i < kGuardReasonCount; ++i)
    if (counts[static_cast<std::size_t>(i)]) j[to_string(static_cast<GuardReason>(i))] = counts[static_cast<std::size_t>(i)];
  return j;
}

json run_summary_json(const hil::ArscRunResult& r) {
  json j = {{"pole_set", to_string(r.config.poles)},
            {"variant", hil::to_string(r.config.variant)},
            {"sample_s", r.config.process.sample_s},
            {"force_ref", r.config.force_ref},
            {"settle_s", r.config.settle_s},
            {"force_error_max_pct", r.force_error_max_pct},
            {"force_error_rms_pct", r.force_error_rms_pct},
            {"samples_over_10pct", r.samples_over_10pct},
            {"force_noise", {{"rms", r.config.force_noise.rms}, {"seed", r.config.force_noise.seed}}},
            {"diverged", r.diverged},
            {"diverged_at_s", r.diverged_at_s ? json(*r.diverged_at_s) : json(nullptr)},
            {"first_gains_s", r.first_gains_s ? json(*r.first_gains_s) : json(nullptr)},
            {"gain_updates", reasons_json(r.reason_counts)}};
  j["final_gains"] = r.trace.empty() ? json(nullptr) : all_gains_json(r.trace.back().gains);
  if (r.config.variant == hil::ArscVariant::faithful) {
    j["estimator"] = {{"kind", "ARV(2) RLS, S3 eq. (5)"},
                      {"forgetting", r.config.faithful_rls.forgetting},
                      {"initial_covariance", r.config.faithful_rls.initial_covariance}};
  } else {
    j["estimator"] = {{"kind", "cutting gain only, scalar RLS"},
                      {"forgetting", r.config.robust_forgetting},
                      {"gain_trend_alpha", hil::robust_gain_trend_alpha(r.config)},
                      {"initial_covariance", r.config.robust_initial_covariance}};
  }
  if (r.test_stage) {
    const StructuredModel& m = r.test_stage->model;
    j["test_stage"] = {{"a11", m.drive.a11}, {"b11", m.drive.b11}, {"c11", m.drive.c11},
                       {"a21", m.a21},       {"g", m.cutting_gain}, {"samples", r.test_stage->samples}};
  }
  j["process"] = {{"a11", r.process_coefficients.a11}, {"b11", r.process_coefficients.b11},
                  {"a21", r.process_coefficients.a21}, {"b21", r.process_coefficients.b21}};
  return j;
}

json trace_json(const hil::ArscRunResult& r) {
  json out = json::array();
  for (const hil::ArscTracePoint& p : r.trace) {
    json e = {{"t_s", p.t_s},     {"depth_mm", p.depth_mm}, {"force", p.force}, {"force_measured", p.force_measured},
              {"feed", p.feed},   {"u", p.u},               {"have_gains", p.have_gains},
              {"reason", to_string(p.reason)}, {"gains", design_gains_json(p.gains)},
              {"cutting_gain_estimate", p.cutting_gain}, {"cutting_gain_process", p.true_cutting_gain}};
    if (r.config.variant == hil::ArscVariant::faithful) e["theta"] = p.theta;
    out.push_back(e);
  }
  return out;
}

void print_run_text(const hil::ArscRunResult& r) {
  std::printf("S3 ARSC %s, %s, T = %.2f s, f* = %.2f, depth %.1f -> %.1f -> %.1f mm over %.0f s\n",
              hil::to_string(r.config.variant), to_string(r.config.poles), r.config.process.sample_s,
              r.config.force_ref, r.config.depth.start_mm, r.config.depth.peak_mm, r.config.depth.start_mm,
              r.config.duration_s);
  if (r.config.force_noise.rms > 0.0)
    std::printf("  force measured with noise %.3g rms (of f*), seed %llu; the process' force is scored\n",
                r.config.force_noise.rms, static_cast<unsigned long long>(r.config.force_noise.seed));
  std::printf("  force error after %.0f s: max %.2f%%  rms %.2f%%  (%zu of %zu samples over 10%%)%s\n",
              r.config.settle_s, r.force_error_max_pct, r.force_error_rms_pct, r.samples_over_10pct,
              r.scored_samples, r.diverged ? "" : "");
  if (r.diverged) std::printf("  DIVERGED at t = %.2f s\n", *r.diverged_at_s);
  std::printf("  gain updates:");
  for (int i = 0; i < kGuardReasonCount; ++i)
    if (r.reason_counts[static_cast<std::size_t>(i)])
      std::printf(" %s %u", to_string(static_cast<GuardReason>(i)), r.reason_counts[static_cast<std::size_t>(i)]);
  std::printf("\n");
  std::printf("  %6s %6s %8s %8s %8s %9s %9s %9s %9s %8s  %s\n", "t_s", "depth", "f", "v", "u", "k", "gamma01",
              "gamma11", "gamma31", "g_est", "update");
  for (std::size_t i = 0; i < r.trace.size(); i += 10) {
    const hil::ArscTracePoint& p = r.trace[i];
    std::printf("  %6.2f %6.3f %8.4f %8.4f %8.4f %9.4g %9.4g %9.4g %9.4g %8.4f  %s\n", p.t_s, p.depth_mm, p.force,
                p.feed, p.u, p.gains.k, p.gains.gamma01, p.gains.gamma11, p.gains.gamma31, p.cutting_gain,
                to_string(p.reason));
  }
}

int run_run(const RunOptions& o) {
  const auto noise = force_noise_or_report(o.scenario);
  if (!noise) return kExitBadInput;
  hil::ArscRunConfig config = run_config(o.poles, o.variant, o.forgetting, o.p0);
  config.force_noise = *noise;
  config.robust_gain_trend_alpha = o.trend_alpha;
  const hil::ArscRunResult r = hil::run_arsc(config);
  if (o.json) {
    json j = run_summary_json(r);
    j["trace"] = trace_json(r);
    std::cout << j.dump(1) << '\n';
  } else {
    print_run_text(r);
  }
  if (!o.plot.empty() && !write_figure(o.plot, hil::arsc_run_plot_data(r))) return kExitFailure;
  return kExitOk;
}

struct CompareOptions {
  bool json = false;
  std::string plot;
  std::string scenario;  // empty: the paper's noiseless measurement
  int seeds = 1;         // noise seeds (with --scenario)
};

json sweep_json(const hil::ArscSeedSweep& s) {
  json j = run_summary_json(s.first);
  j["seeds"] = s.seeds;
  j["force_error_max_pct_worst"] = s.force_error_max_pct_worst;
  j["force_error_rms_pct_mean"] = s.force_error_rms_pct_mean;
  j["diverged_runs"] = s.diverged_runs;
  return j;
}

int run_compare(const CompareOptions& o) {
  const auto noise = force_noise_or_report(o.scenario);
  if (!noise) return kExitBadInput;
  const int seeds = noise->rms > 0.0 ? o.seeds : 1;  // without noise every seed is the same run
  std::vector<hil::ArscSeedSweep> faithful, robust;
  for (const char* set : {"case1", "case2", "case3", "case4"}) {
    for (const char* variant : {"faithful", "robust"}) {
      hil::ArscRunConfig c = run_config(set, variant, -1.0, -1.0);
      c.force_noise = *noise;
      (variant[0] == 'f' ? faithful : robust).push_back(hil::run_arsc_seeds(c, seeds));
    }
  }
  if (o.json) {
    json j = json::array();
    for (std::size_t i = 0; i < 4; ++i) {
      j.push_back(o.scenario.empty() ? run_summary_json(faithful[i].first) : sweep_json(faithful[i]));
      j.push_back(o.scenario.empty() ? run_summary_json(robust[i].first) : sweep_json(robust[i]));
    }
    std::cout << json{{"runs", j}}.dump(2) << '\n';
  } else {
    std::printf("S3 ARSC, T = 0.15 s, depth 0.2 -> 1.0 -> 0.2 mm over 30 s; force error after 3 s, %% of f*\n");
    if (!o.scenario.empty())
      std::printf("force measured with %s's force ADC noise: %.3g of f* rms (f* = %.0f N), %d noise seed%s from %llu;\n"
                  "worst max and mean rms over the seeds, of the process' force\n",
                  o.scenario.c_str(), noise->rms, hil::kS3ForceReferenceN, seeds, seeds == 1 ? "" : "s",
                  static_cast<unsigned long long>(noise->seed));
    std::printf("  %-6s | %-32s | %-32s\n", "poles", "faithful (paper, corrected)", "robust");
    for (std::size_t i = 0; i < 4; ++i) {
      char a[64], b[64];
      const auto cell = [](char* buf, const hil::ArscSeedSweep& s) {
        if (s.diverged_runs == s.seeds)
          std::snprintf(buf, 64, "diverged at %.2f s", *s.first.diverged_at_s);
        else if (s.diverged_runs > 0)
          std::snprintf(buf, 64, "diverged in %d of %d runs", s.diverged_runs, s.seeds);
        else
          std::snprintf(buf, 64, "max %7.2f  rms %7.2f", s.force_error_max_pct_worst, s.force_error_rms_pct_mean);
      };
      cell(a, faithful[i]);
      cell(b, robust[i]);
      std::printf("  %-6s | %-32s | %-32s\n", to_string(faithful[i].first.config.poles), a, b);
    }
  }
  std::vector<hil::ArscRunResult> faithful_first, robust_first;
  for (std::size_t i = 0; i < 4; ++i) {
    faithful_first.push_back(faithful[i].first);
    robust_first.push_back(robust[i].first);
  }
  if (!o.plot.empty() && !write_figure(o.plot, hil::arsc_compare_plot_data(faithful_first, robust_first)))
    return kExitFailure;
  return kExitOk;
}

struct TickOptions {
  int period_ms = 0;  // 0: the comparison of rates
  std::string poles = "case1";
  std::string path = "line";
  double speedup = 1.0;
  bool fixed_gain = false;
  bool json = false;
  std::string plot;
  std::string scenario;  // empty: the reference table
  int seeds = 1;         // --period-ms: runs on seeded tables 0 .. seeds-1 (hil::seeded)
  double step_ramp_mm = hil::StockStepCase{}.step_ramp_mm;  // --path stock-step
};

// The comparison behind "what the faster loop buys": no force loop, the
// paper's rate, faster rates at the same poles, and the fast loop with
// poles it alone can use.
std::vector<hil::TickStudyConfig> tick_comparison(PoleSet set, hil::StudyPath path, const emu::Scenario& table) {
  std::vector<hil::TickStudyConfig> out;
  hil::TickStudyConfig c;
  c.table = table;
  c.poles = set;
  c.path = path;
  c.label = "constant feed";
  c.outer_loop = false;
  out.push_back(c);
  c.outer_loop = true;
  const struct {
    const char* label;
    std::uint32_t ticks;
    double speedup;
  } rows[] = {{"0.15 s", 150, 1.0}, {"0.15 s, 4x poles", 150, 4.0}, {"10 ms", 10, 1.0}, {"1 ms", 1, 1.0},
              {"1 ms, 4x poles", 1, 4.0}};
  for (const auto& row : rows) {
    c.label = row.label;
    c.ticks_per_sample = row.ticks;
    c.pole_speedup = row.speedup;
    out.push_back(c);
  }
  return out;
}

void print_stock_step_line(const hil::TickStudyResult& r) {
  const hil::StockStepCase& k = r.config.stock;
  if (r.step_at_s < 0.0) {
    std::printf("  %-26s the step was not reached\n", "");
    return;
  }
  std::printf("  %-26s step at %.3f s: a_p %.2f -> %.2f mm, feed %.2f -> %.2f mm/s; %.1f s after: force error "
              "%.2f %% (ADC %.2f %%), worst from then %.2f %% (ADC %.2f %%); crashes %llu\n",
              "", r.step_at_s, r.depth_before_mm, r.depth_after_mm, r.feed_before_mm_s, r.feed_after_mm_s,
              k.judged_after_s, r.step_error_pct, r.step_error_measured_pct, r.after_step_max_pct,
              r.after_step_measured_max_pct, static_cast<unsigned long long>(r.crashes));
}

void print_tick_text(const std::vector<hil::TickStudyResult>& runs) {
  const hil::TickStudyConfig& c0 = runs.front().config;
  if (c0.path == hil::StudyPath::stock_step) {
    const hil::StockStepCase& k = c0.stock;
    std::printf("Robust ARSC as the firmware's feed-override source (emulated TNV-40), stock-step path, f* = %.0f N, "
                "%s,\nthe force where the tool is ([stock]), spindle %.0f rpm, a_p %.1f -> %.1f mm stepping down in Z "
                "over %.1f mm of X, %.0f mm into the cut;\nforce error after %.0f s, every tick, %% of f*\n",
                c0.force_ref_n, to_string(c0.poles), k.spindle_rpm, k.start_depth_mm, k.start_depth_mm + k.step_mm,
                k.step_ramp_mm, k.step_after_mm, c0.settle_s);
  } else {
    std::printf("Robust ARSC as the firmware's feed-override source (emulated TNV-40), %s path, f* = %.0f N, %s,\n"
                "depth %.1f -> %.1f -> %.1f mm over %.0f + %.0f s; force error after %.0f s, every tick, %% of f*\n",
                hil::to_string(c0.path), c0.force_ref_n, to_string(c0.poles), c0.milling.depth.start_mm,
                c0.milling.depth.peak_mm, c0.milling.depth.start_mm, c0.milling.depth.rise_s, c0.milling.depth.fall_s,
                c0.settle_s);
  }
  if (c0.table.name != emu::Scenario{}.name)
    std::printf("on %s (its noise, transport and plant; the study's milling force); in brackets: against the "
                "milling force itself\n",
                c0.table.name.c_str());
  const hil::TickTestStage& ts = runs.front().test_stage;
  std::printf("test stage: T_f %.4f s, G %.4f N per mm/s at %.1f mm, feed lag %.2f ms (gain %.3f)\n",
              ts.force_time_constant_s, ts.cutting_gain_n_per_mm_s,
              c0.path == hil::StudyPath::stock_step ? c0.stock.start_depth_mm : c0.milling.depth.start_mm,
              ts.drive_time_constant_s * 1e3, ts.drive_gain);
  std::printf("  %-26s %9s %9s %9s  %-9s %10s %8s %10s\n", "loop", "period", "max %", "rms %", "diverged",
              "DAC sat.", "clamped", "max |gain|");
  for (const hil::TickStudyResult& r : runs) {
    if (!r.error.empty()) {
      std::printf("  %-26s not run: %s\n", r.config.label.c_str(), r.error.c_str());
      continue;
    }
    char period[32];
    if (r.config.outer_loop)
      std::snprintf(period, sizeof period, "%g ms", r.period_s * 1e3);
    else
      std::snprintf(period, sizeof period, "-");
    char diverged[48];
    std::snprintf(diverged, sizeof diverged, r.diverged ? "at %.2f s" : "no", r.diverged_at_s);
    std::printf("  %-26s %9s %9.2f %9.2f  %-9s %10llu %8u %10.3g\n", r.config.label.c_str(), period,
                r.force_error_max_pct, r.force_error_rms_pct, diverged,
                static_cast<unsigned long long>(r.dac_saturated_ticks), r.clamped_samples,
                r.config.outer_loop ? r.max_abs_gain : 0.0);
    if (c0.table.name != emu::Scenario{}.name)
      std::printf("  %-26s %9s %9.2f %9.2f  (the milling force)\n", "", "", r.force_error_true_max_pct,
                  r.force_error_true_rms_pct);
    if (r.config.path == hil::StudyPath::stock_step) print_stock_step_line(r);
    if (!r.fault.empty()) std::printf("  %-26s firmware fault: %s\n", "", r.fault.c_str());
    if (r.program_end_s >= 0.0) std::printf("  %-26s the program ran out at %.2f s\n", "", r.program_end_s);
  }
}

int run_tick(const TickOptions& o) {
  const PoleSet set = *parse_pole_set(o.poles);
  const hil::StudyPath path = *hil::parse_study_path(o.path);
  emu::Scenario table{};
  if (!o.scenario.empty()) {
    const auto resolved = resolve_scenario_or_report(o.scenario);
    if (!resolved) return kExitBadInput;
    table = *resolved;
  }
  std::vector<hil::TickStudyConfig> configs;
  if (o.period_ms > 0) {
    hil::TickStudyConfig c;
    c.table = table;
    c.poles = set;
    c.path = path;
    c.ticks_per_sample = static_cast<std::uint32_t>(o.period_ms);
    c.pole_speedup = o.speedup;
    c.adapt = !o.fixed_gain;
    char label[64];
    std::snprintf(label, sizeof label, "%d ms", o.period_ms);
    const std::size_t used = std::strlen(label);
    const char* fixed = o.fixed_gain ? ", fixed G" : "";
    if (o.speedup != 1.0)
      std::snprintf(label + used, sizeof label - used, ", %gx poles%s", o.speedup, fixed);
    else
      std::snprintf(label + used, sizeof label - used, "%s", fixed);
    c.label = label;
    c.stock.step_ramp_mm = o.step_ramp_mm;
    for (int seed = 0; seed < o.seeds; ++seed) {
      c.table = hil::seeded(table, seed);
      if (o.seeds > 1) c.label = std::string(label) + ", seed " + std::to_string(seed);
      configs.push_back(c);
    }
  } else {
    configs = tick_comparison(set, path, table);
  }
  std::vector<hil::TickStudyResult> runs;
  for (const auto& c : configs) runs.push_back(hil::run_tick_study(c));  // about 50 ms each
  if (o.json) {
    if (o.period_ms > 0 && o.seeds == 1) {
      std::cout << hil::tick_study_json(runs.front()).dump(2) << '\n';
    } else {
      json j = json::array();
      for (const auto& r : runs) j.push_back(hil::tick_study_json(r));
      std::cout << json{{"runs", j}}.dump(2) << '\n';
    }
  } else {
    print_tick_text(runs);
  }
  if (!o.plot.empty() && !write_figure(o.plot, hil::arsc_tick_plot_data(runs))) return kExitFailure;
  for (const auto& r : runs)
    if (!r.error.empty() || !r.fault.empty() || r.crashes > 0) return kExitFailure;
  return kExitOk;
}

}  // namespace

void add_arsc_commands(CLI::App& app, Runner& run) {
  CLI::App* arsc = app.add_subcommand("arsc", "S3 adaptive cutting-force regulation (ARSC)");
  arsc->require_subcommand(1);
  const auto pole_check = CLI::IsMember({"case1", "case2", "case3", "case4"});

  auto design = std::make_shared<ArscDesignOptions>();
  CLI::App* d = arsc->add_subcommand("design", "the paper's gains (25)+(26) at its starting estimates (29), or 'singular'");
  d->add_option("--poles", design->poles, "case1 | case2 | case3 | case4 (S3 Fig. 7)")->required()->check(pole_check);
  d->add_flag("--json", design->json, "print JSON on stdout");
  d->callback([&run, design] { run = [design] { return run_arsc_design(*design); }; });

  auto r = std::make_shared<RunOptions>();
  CLI::App* rc = arsc->add_subcommand("run", "one 30 s S3 simulation run (T = 0.15 s, depth 0.2 -> 1.0 -> 0.2 mm)");
  rc->add_option("--poles", r->poles, "case1 | case2 | case3 | case4 (S3 Fig. 7)")->required()->check(pole_check);
  rc->add_option("--variant", r->variant, "faithful (the paper's loop) | robust")
      ->required()
      ->check(CLI::IsMember({"faithful", "robust"}));
  rc->add_flag("--json", r->json, "print JSON on stdout (summary and the trace)");
  rc->add_option("--plot", r->plot, "write the run's figure (.svg, .png or .pdf)")->check(tnv::cli::PlotFile());
  rc->add_option("--forgetting", r->forgetting, "estimator forgetting factor (default: faithful 0.98, robust 0.05)")
      ->check(CLI::Range(1e-6, 1.0));
  rc->add_option("--p0", r->p0, "estimator initial covariance (default: faithful 1, robust 10)")
      ->check(CLI::PositiveNumber);
  const char* s3_scenario_help =
      "measure the force with this table's force ADC noise (built-in name or TOML file; [noise] force_adc_v_rms "
      "over [force_sensor] volts_per_n, f* = 150 N; [noise] seed); default: the paper's noiseless force";
  rc->add_option("--scenario", r->scenario, s3_scenario_help);
  rc->add_option("--trend-alpha", r->trend_alpha,
                 "robust: alpha of the gain design's tracker, 1 = off (default: 1 without noise, 0.35 with --scenario noise)")
      ->check(CLI::Range(0.01, 1.0));
  rc->callback([&run, r] { run = [r] { return run_run(*r); }; });

  auto cmp = std::make_shared<CompareOptions>();
  CLI::App* cc = arsc->add_subcommand("compare", "both variants, four pole sets, side by side");
  cc->add_flag("--json", cmp->json, "print JSON on stdout");
  cc->add_option("--plot", cmp->plot, "write the comparison figure (.svg, .png or .pdf)")->check(tnv::cli::PlotFile());
  CLI::Option* cmp_scenario = cc->add_option("--scenario", cmp->scenario, s3_scenario_help);
  cc->add_option("--seeds", cmp->seeds, "noise seeds [noise] seed + 0 .. N-1 per run: worst max, mean rms (with --scenario)")
      ->check(CLI::Range(1, 1000))
      ->needs(cmp_scenario)
      ->capture_default_str();
  cc->callback([&run, cmp] { run = [cmp] { return run_compare(*cmp); }; });

  auto tick = std::make_shared<TickOptions>();
  CLI::App* tc = arsc->add_subcommand(
      "tick", "robust ARSC as the firmware's feed-override source on the emulated TNV-40, 150 N, a program of "
              "planner segments; without --period-ms: constant feed, 0.15 s, 10 ms and 1 ms side by side");
  CLI::Option* period = tc->add_option("--period-ms", tick->period_ms, "one run with this outer-loop period (whole 1 ms ticks)")
                            ->check(CLI::Range(1, 500));
  tc->add_option("--poles", tick->poles, "case1 | case2 | case3 | case4 (S3 Fig. 7, force-loop pair)")
      ->check(pole_check);
  tc->add_option("--path", tick->path,
                 "line (along X) | arc (a line, a 45 deg tangent arc, a 45 deg line) | stock-step (the force where the "
                 "tool is, [stock] on, spindle at 6000 rpm, a_p 1 -> 2 mm by a step down in Z; docs/reproduction-s3.md)")
      ->check(CLI::IsMember({"line", "arc", "stock-step"}));
  tc->add_option("--speedup", tick->speedup, "force-loop poles this many times faster than the paper's (with --period-ms)")
      ->check(CLI::Range(0.1, 20.0))
      ->needs(period);
  tc->add_option("--step-ramp-mm", tick->step_ramp_mm,
                 "--path stock-step: X travel over which Z steps down 1 mm (1: a 45 deg ramp, whose corner the planner "
                 "takes slowly; longer: a gentler corner, a slower step)")
      ->check(CLI::Range(0.1, 50.0))
      ->needs(period)
      ->capture_default_str();
  tc->add_option("--seeds", tick->seeds,
                 "with --period-ms: one run on each seeded table 0 .. N-1 (encoder phases; noise seeds with "
                 "--scenario [noise])")
      ->check(CLI::Range(1, 100))
      ->needs(period)
      ->capture_default_str();
  tc->add_flag("--fixed-gain", tick->fixed_gain,
               "freeze the cutting-gain estimate at the test stage's (no adaptation; with --period-ms)")
      ->needs(period);
  tc->add_option("--scenario", tick->scenario,
                 "run on this table (built-in name or TOML file): its noise, transport and plant apply, its [milling] "
                 "is the study's; default: the reference table");
  tc->add_flag("--json", tick->json, "print JSON on stdout");
  tc->add_option("--plot", tick->plot, "write the figure (.svg, .png or .pdf)")->check(tnv::cli::PlotFile());
  tc->callback([&run, tick] { run = [tick] { return run_tick(*tick); }; });
}

}  // namespace tnv::cli
