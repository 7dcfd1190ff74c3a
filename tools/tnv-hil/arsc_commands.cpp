// tnv-hil arsc design | run | compare | tick: S3 adaptive cutting-force
// regulation (ARSC), the paper's loop and the robust variant.
#include <CLI/CLI.hpp>
#include <Eigen/Eigenvalues>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "firmware/adaptive/arsc/closed_loop_matrix.hpp"
#include "firmware/adaptive/arsc/faithful_gain_solve.hpp"
#include "tools/hil/arsc_plot.hpp"
#include "tools/hil/arsc_run.hpp"
#include "tools/hil/arsc_tick_study.hpp"
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

struct DesignOptions {
  std::string poles = "case1";
  bool json = false;
};

int run_design(const DesignOptions& o) {
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
    const Eigen::EigenSolver<Matrix7> es(a);
    for (int i = 0; i < 7; ++i) poles.push_back({es.eigenvalues()(i).real(), es.eigenvalues()(i).imag()});
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
};

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
    json e = {{"t_s", p.t_s},     {"depth_mm", p.depth_mm}, {"force", p.force},
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
  const hil::ArscRunResult r = hil::run_arsc(run_config(o.poles, o.variant, o.forgetting, o.p0));
  if (o.json) {
    json j = run_summary_json(r);
    j["trace"] = trace_json(r);
    std::cout << j.dump(1) << '\n';
  } else {
    print_run_text(r);
  }
  if (!o.plot.empty() && !write_svg(o.plot, hil::arsc_run_figure(r))) return kExitFailure;
  return kExitOk;
}

struct CompareOptions {
  bool json = false;
  std::string plot;
};

int run_compare(const CompareOptions& o) {
  std::vector<hil::ArscRunResult> faithful, robust;
  for (const char* set : {"case1", "case2", "case3", "case4"}) {
    faithful.push_back(hil::run_arsc(run_config(set, "faithful", -1.0, -1.0)));
    robust.push_back(hil::run_arsc(run_config(set, "robust", -1.0, -1.0)));
  }
  if (o.json) {
    json j = json::array();
    for (std::size_t i = 0; i < 4; ++i) {
      j.push_back(run_summary_json(faithful[i]));
      j.push_back(run_summary_json(robust[i]));
    }
    std::cout << json{{"runs", j}}.dump(2) << '\n';
  } else {
    std::printf("S3 ARSC, T = 0.15 s, depth 0.2 -> 1.0 -> 0.2 mm over 30 s; force error after 3 s, %% of f*\n");
    std::printf("  %-6s | %-32s | %-32s\n", "poles", "faithful (paper, corrected)", "robust");
    for (std::size_t i = 0; i < 4; ++i) {
      char a[64], b[64];
      const auto cell = [](char* buf, const hil::ArscRunResult& r) {
        if (r.diverged)
          std::snprintf(buf, 64, "diverged at %.2f s", *r.diverged_at_s);
        else
          std::snprintf(buf, 64, "max %7.2f  rms %7.2f", r.force_error_max_pct, r.force_error_rms_pct);
      };
      cell(a, faithful[i]);
      cell(b, robust[i]);
      std::printf("  %-6s | %-32s | %-32s\n", to_string(faithful[i].config.poles), a, b);
    }
  }
  if (!o.plot.empty() && !write_svg(o.plot, hil::arsc_compare_figure(faithful, robust))) return kExitFailure;
  return kExitOk;
}

struct TickOptions {
  bool json = false;
  std::string plot;
};

int run_tick(const TickOptions& o) {
  std::vector<hil::TickStudyConfig> configs;
  {
    hil::TickStudyConfig c;
    c.label = "0.15 s, paper poles";
    c.ticks_per_sample = 150;
    configs.push_back(c);
    c.label = "1 ms, paper poles";
    c.ticks_per_sample = 1;
    configs.push_back(c);
    c.label = "1 ms, fast poles kept";
    c.keep_fast_poles = true;
    configs.push_back(c);
  }
  std::vector<hil::TickStudyResult> runs;
  for (const auto& c : configs) runs.push_back(hil::run_tick_study(c));
  json j = json::array();
  for (const auto& r : runs) {
    const StructuredModel& m = r.test_stage.model;
    j.push_back({{"label", r.config.label},
                 {"period_s", 1e-3 * r.config.ticks_per_sample},
                 {"pole_speedup", r.config.pole_speedup},
                 {"error", r.error},
                 {"force_error_max_pct", r.force_error_max_pct},
                 {"force_error_rms_pct", r.force_error_rms_pct},
                 {"diverged", r.diverged},
                 {"travel_mm", r.travel_mm},
                 {"refused_updates", r.refused_updates},
                 {"initial_gamma01", r.initial_gamma01},
                 {"initial_max_abs_gain", r.initial_max_abs_gain},
                 {"first_saturation_s", r.first_saturation_s},
                 {"test_stage", {{"a11", m.drive.a11}, {"b11", m.drive.b11}, {"c11", m.drive.c11},
                                 {"a21", m.a21}, {"g", m.cutting_gain}, {"bias", r.test_stage.drive_bias}}}});
  }
  if (o.json) {
    std::cout << json{{"runs", j}}.dump(2) << '\n';
  } else {
    std::printf("Robust ARSC on the emulated TNV-40 X axis, 150 N, depth 0.2 -> 1.0 -> 0.2 mm over 12 s\n");
    for (const auto& r : runs) {
      if (!r.error.empty()) {
        std::printf("  %-40s  not run: %s\n", r.config.label.c_str(), r.error.c_str());
        continue;
      }
      std::printf("  %-38s  force error after 3 s: max %7.2f%%  rms %7.2f%%  travel %7.1f mm\n",
                  r.config.label.c_str(), r.force_error_max_pct, r.force_error_rms_pct, r.travel_mm);
      std::printf("  %-38s  design: gamma01 %.3f, largest gain %.3g; DAC saturated first at %s\n", "",
                  r.initial_gamma01, r.initial_max_abs_gain,
                  r.first_saturation_s < 0.0 ? "never" : (std::to_string(r.first_saturation_s) + " s").c_str());
    }
  }
  if (!o.plot.empty() && !write_svg(o.plot, hil::arsc_tick_figure(runs))) return kExitFailure;
  return kExitOk;
}

}  // namespace

void add_arsc_commands(CLI::App& app, Runner& run) {
  CLI::App* arsc = app.add_subcommand("arsc", "S3 adaptive cutting-force regulation (ARSC)");
  arsc->require_subcommand(1);
  const auto pole_check = CLI::IsMember({"case1", "case2", "case3", "case4"});

  auto design = std::make_shared<DesignOptions>();
  CLI::App* d = arsc->add_subcommand("design", "the paper's gains (25)+(26) at its starting estimates (29), or 'singular'");
  d->add_option("--poles", design->poles, "case1 | case2 | case3 | case4 (S3 Fig. 7)")->required()->check(pole_check);
  d->add_flag("--json", design->json, "print JSON on stdout");
  d->callback([&run, design] { run = [design] { return run_design(*design); }; });

  auto r = std::make_shared<RunOptions>();
  CLI::App* rc = arsc->add_subcommand("run", "one 30 s S3 simulation run (T = 0.15 s, depth 0.2 -> 1.0 -> 0.2 mm)");
  rc->add_option("--poles", r->poles, "case1 | case2 | case3 | case4 (S3 Fig. 7)")->required()->check(pole_check);
  rc->add_option("--variant", r->variant, "faithful (the paper's loop) | robust")
      ->required()
      ->check(CLI::IsMember({"faithful", "robust"}));
  rc->add_flag("--json", r->json, "print JSON on stdout (summary and the trace)");
  rc->add_option("--plot", r->plot, "write the run's figure (SVG)");
  rc->add_option("--forgetting", r->forgetting, "estimator forgetting factor (default: faithful 0.98, robust 0.05)")
      ->check(CLI::Range(1e-6, 1.0));
  rc->add_option("--p0", r->p0, "estimator initial covariance (default: faithful 1, robust 10)")
      ->check(CLI::PositiveNumber);
  rc->callback([&run, r] { run = [r] { return run_run(*r); }; });

  auto cmp = std::make_shared<CompareOptions>();
  CLI::App* cc = arsc->add_subcommand("compare", "both variants, four pole sets, side by side");
  cc->add_flag("--json", cmp->json, "print JSON on stdout");
  cc->add_option("--plot", cmp->plot, "write the comparison figure (SVG)");
  cc->callback([&run, cmp] { run = [cmp] { return run_compare(*cmp); }; });

  auto tick = std::make_shared<TickOptions>();
  CLI::App* tc = arsc->add_subcommand("tick", "robust ARSC on the emulated TNV-40 X axis at 150 N (0.15 s, 10 ms, 1 ms)");
  tc->add_flag("--json", tick->json, "print JSON on stdout");
  tc->add_option("--plot", tick->plot, "write the figure (SVG)");
  tc->callback([&run, tick] { run = [tick] { return run_tick(*tick); }; });
}

}  // namespace tnv::cli
