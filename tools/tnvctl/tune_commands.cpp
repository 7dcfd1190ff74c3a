// tnvctl identify | autotune: identification over CAN (EXCITE + capture,
// the rig's sequence and fit) and the automatic design applied as one
// atomic parameter set (docs/autotune.md).
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include "tools/can/autotune_plan.hpp"
#include "tools/can/can_identify.hpp"
#include "tools/can/param_text.hpp"
#include "tools/can/tune_json.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

struct TuneOptions {
  std::string axis = "both";
  bool dry_run = false;
  bool yes = false;
};

std::vector<hal::Axis> axes_of(const std::string& name) {
  if (const std::optional<hal::Axis> a = hal::axis_from_name(name)) return {*a};
  if (name == "both") return {hal::kAxes.begin(), hal::kAxes.end()};
  std::string names;  // "x, y"
  for (const char* n : hal::kAxisNames) names.append(names.empty() ? "" : ", ").append(n);
  std::string message = "--axis must be an axis (" + names + ") or both, not '";
  throw BadInput(message.append(name).append("'"));
}

const char* tune_axis_name(hal::Axis a) { return hal::axis_label(a); }

// Progress on stderr once the run has taken a second of wall time.
class IdentifyProgressLine {
 public:
  void operator()(const std::string& text) {
    const auto now = std::chrono::steady_clock::now();
    if (!started_) {
      started_ = true;
      start_ = now;
    }
    if (now - start_ < std::chrono::seconds(1)) return;
    std::fprintf(stderr, "[identify] %s\n", text.c_str());
    std::fflush(stderr);
  }

 private:
  bool started_ = false;
  std::chrono::steady_clock::time_point start_{};
};

std::vector<tune::AxisIdentification> identify_axes(const std::vector<hal::Axis>& axes, Session& session) {
  can_host::NodeClient& client = session.client();
  IdentifyProgressLine progress;
  std::vector<tune::AxisIdentification> out;
  for (const hal::Axis a : axes) {
    tune::AxisIdentification id = can_host::identify_axis_over_can(client, a, std::ref(progress));
    if (!id.ok) {
      std::string message = "axis ";
      throw RunFailed(message.append(tune_axis_name(a)).append(": the fit failed: ").append(id.error));
    }
    out.push_back(std::move(id));
  }
  return out;
}

std::string mode_text(const tune::AxisIdentification& id) {
  if (!id.mode_found) return id.mode_fit.note.empty() ? "none" : "none (" + id.mode_fit.note + ")";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f Hz, zeta %.4f", id.mode_hz, id.mode_zeta);
  return buf;
}

std::string identification_row(const tune::AxisIdentification& id) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%-4s %9.3f %9.5f %11.4f %11.4f   [%.6f %.6e; %.6f %.6f]   [%.6e; %.6f]",
                tune_axis_name(id.axis), id.tau_s * 1e3, id.gain, id.coulomb_mm_s, id.stiction_mm_s, id.model.A(0, 0),
                id.model.A(0, 1), id.model.A(1, 0), id.model.A(1, 1), id.model.B(0), id.model.B(1));
  return buf;
}

void report_identifications(const std::vector<tune::AxisIdentification>& ids, Report& report) {
  report.line("axis  tau (ms)         K  f_c (mm/s)  f_s (mm/s)   A = [a11 a12; a21 a22]                         "
              "B = [b1; b2]");
  nlohmann::json list = nlohmann::json::array();
  for (const tune::AxisIdentification& id : ids) {
    report.line(identification_row(id));
    list.push_back(can_host::identification_json(id));
  }
  for (const tune::AxisIdentification& id : ids) {
    std::string line = tune_axis_name(id.axis);
    report.line(line.append(" structural mode (tool accelerometer): ").append(mode_text(id)));
  }
  char buf[160];
  std::snprintf(buf, sizeof buf, "(A, B: 1 ms zero-order hold of tau, K; Stribeck speed not identified, %.1f mm/s assumed)",
                tune::kAssumedStribeck_mm_s);
  report.line(buf);
  report.data["axes"] = list;
}

int run_identify(const TuneOptions& o, Session& session, Report& report) {
  const std::vector<tune::AxisIdentification> ids = identify_axes(axes_of(o.axis), session);
  report_identifications(ids, report);
  return kExitOk;
}

std::string loop_text(const can_host::LoopPrediction& p) {
  if (!p.ok) return "n/a (" + p.why + ")";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.4f", p.spectral_radius);
  std::string out = buf;
  return out.append("  poles ").append(can_host::poles_text(p.poles));
}

void report_plan(const can_host::AxisPlan& plan, Report& report) {
  const tune::AxisIdentification& id = plan.id;
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s: identified tau %.3f ms, K %.5f, f_c %.4f mm/s, f_s %.4f mm/s", tune_axis_name(id.axis),
                id.tau_s * 1e3, id.gain, id.coulomb_mm_s, id.stiction_mm_s);
  report.line(buf);
  std::string mode = "  structural mode: ";
  mode.append(mode_text(id));
  if (plan.design.shaper.enabled) mode.append(" -> input shaper below");
  else mode.append("; shaper left as it is").append(plan.design.shaper.note.empty() ? "" : " (" + plan.design.shaper.note + ")");
  report.line(mode);
  report.line("  parameter                         now            -> design");
  for (const can_host::ParamChange& c : plan.changes) {
    std::snprintf(buf, sizeof buf, "  %-32s %-14s -> %s%s", c.param->name,
                  can_host::format_param_value(*c.param, c.old_value).c_str(),
                  can_host::format_param_value(*c.param, c.new_value).c_str(),
                  static_cast<float>(c.old_value) == static_cast<float>(c.new_value) ? "  (same)" : "");
    report.line(buf);
  }
  const fw::SlidingModeParams& s = plan.design.sliding;
  std::snprintf(buf, sizeof buf,
                "  theorems: phi %.4f > eta/(q+1) = %.4f mm/s (Theorem 2); 0 < gamma %.4f < min(1-g, q) = %.4f "
                "(Theorem 5)",
                s.phi_mm_s, s.eta_mm_s / (s.q + 1.0), s.gamma, std::min(1.0 - s.g, s.q));
  report.line(buf);
  const fw::FrictionFeedForward& f = plan.design.friction;
  std::snprintf(buf, sizeof buf,
                "  friction feed-forward: %s, f_c %.4f mm/s, f_s %.4f mm/s (Coulomb only), v_s %.2f mm/s, K %.5f, "
                "fraction %.2f",
                f.enabled ? "on" : "off", f.coulomb_mm_s, f.stiction_mm_s, f.stribeck_mm_s, f.gain, f.fraction);
  report.line(buf);
  report.line("  predicted on the identified model, spectral radius (old -> new):");
  const can_host::AxisPrediction& p = plan.prediction;
  const std::pair<const char*, std::pair<const can_host::LoopPrediction*, const can_host::LoopPrediction*>> loops[] = {
      {"R-DVSC+DDC", {&p.rdvsc_old, &p.rdvsc_new}},
      {"DVSC+DDC", {&p.dvsc_old, &p.dvsc_new}},
      {"PID", {&p.pid_old, &p.pid_new}},
      {"observer", {&p.observer_old, &p.observer_new}}};
  for (const auto& [name, pair] : loops) {
    std::snprintf(buf, sizeof buf, "    %-10s old %s", name, loop_text(*pair.first).c_str());
    report.line(buf);
    std::snprintf(buf, sizeof buf, "    %-10s new %s", "", loop_text(*pair.second).c_str());
    report.line(buf);
  }
  report.line("    (observer: the estimation-error poles of its gains, also while observer.enable is off; the loops");
  report.line("    above are linearised on the measured speed)");
}

void check_autotune(const TuneOptions& o) {
  axes_of(o.axis);
  if (o.dry_run && o.yes) throw BadInput("--dry-run and --yes exclude each other");
  if (!o.dry_run && !o.yes && isatty(STDIN_FILENO) == 0)
    throw BadInput("stdin is not a terminal, so nobody can confirm: give --yes to apply, or --dry-run to see the "
                   "change (nothing was sent)");
}

bool confirmed(std::size_t count, int node) {
  std::fprintf(stderr, "apply these %zu parameters to node %d? [y/N] ", count, node);
  std::fflush(stderr);
  std::string answer;
  if (!std::getline(std::cin, answer)) return false;
  return answer == "y" || answer == "Y" || answer == "yes";
}

int run_autotune(const TuneOptions& o, Session& session, Report& report) {
  check_autotune(o);
  const std::vector<tune::AxisIdentification> ids = identify_axes(axes_of(o.axis), session);
  can_host::NodeClient& client = session.client();
  std::vector<can_host::AxisPlan> plans;
  std::vector<can_host::ParamChange> all;
  nlohmann::json list = nlohmann::json::array();
  for (const tune::AxisIdentification& id : ids) {
    const tune::AxisDesign design = tune::design_axis(id);
    if (!design.ok) {
      std::string message = "axis ";
      throw RunFailed(message.append(tune_axis_name(id.axis)).append(": no design: ").append(design.error));
    }
    plans.push_back(can_host::plan_autotune(client, id, design));
    report_plan(plans.back(), report);
    list.push_back(can_host::plan_json(plans.back()));
    all.insert(all.end(), plans.back().changes.begin(), plans.back().changes.end());
  }
  report.data["axes"] = list;
  report.data["applied"] = false;
  if (o.dry_run) {
    report.line("dry run: nothing applied");
    return kExitOk;
  }
  if (!o.yes && !confirmed(all.size(), session.options().node)) {
    report.line("not confirmed: nothing applied");
    return kExitFailure;
  }
  std::vector<double> read_back;
  try {
    read_back = can_host::apply_changes(client, all);
  } catch (const can_host::RequestError& e) {
    if (e.kind() != can_host::RequestError::Kind::refused) throw;
    std::string message = e.what();
    throw RunFailed(message.append(": nothing applied (every parameter stays as it was)"));
  }
  nlohmann::json back = nlohmann::json::array();
  std::size_t mismatched = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    back.push_back({{"name", all[i].param->name}, {"value", read_back[i]}});
    if (static_cast<float>(read_back[i]) != static_cast<float>(all[i].new_value)) ++mismatched;
  }
  report.data["read_back"] = back;
  if (mismatched != 0) {
    std::string message = std::to_string(mismatched);
    throw RunFailed(message.append(" parameter(s) read back different from the design"));
  }
  report.data["applied"] = true;
  char buf[160];
  std::snprintf(buf, sizeof buf, "applied %zu parameters in one commit; read back equal to the design (`params save` keeps them)",
                all.size());
  report.line(buf);
  return kExitOk;
}

}  // namespace

void add_tune_commands(CLI::App& app, ActionSlot& slot) {
  auto id = std::make_shared<TuneOptions>();
  CLI::App* identify = app.add_subcommand(
      "identify",
      "identify the axis plant (tau, K, Coulomb f_c, stiction f_s; A, B; a structural mode from the tool "
      "accelerometer) from open-loop EXCITE steps and ramps recorded by the node's capture; the node must be "
      "enabled and holding (tnvctl enable; with --emu: `tnvctl --emu script` with enable first)");
  identify->add_option("--axis", id->axis, axis_help_or("both"))
      ->check(CLI::IsMember(axis_values_or("both")))
      ->capture_default_str();
  identify->callback([&slot, id] {
    slot = Action{"identify", true, [id](Session& s, Report& r) { return run_identify(*id, s, r); },
                  [id] { axes_of(id->axis); }};
  });

  auto tune = std::make_shared<TuneOptions>();
  CLI::App* autotune = app.add_subcommand(
      "autotune",
      "identify, design by the stated rules (docs/autotune.md), show old -> new and the predicted closed loops, "
      "then apply everything in one commit (all or nothing); asks first unless --yes");
  autotune->add_option("--axis", tune->axis, axis_help_or("both"))
      ->check(CLI::IsMember(axis_values_or("both")))
      ->capture_default_str();
  autotune->add_flag("--dry-run", tune->dry_run, "identify and show the change; apply nothing");
  autotune->add_flag("--yes", tune->yes, "apply without asking (needed when stdin is not a terminal)");
  autotune->callback([&slot, tune] {
    slot = Action{"autotune", true, [tune](Session& s, Report& r) { return run_autotune(*tune, s, r); },
                  [tune] { check_autotune(*tune); }};
  });
}

}  // namespace tnv::tnvctl
