#include "tools/hil/report.hpp"

#include <cstdio>
#include <map>

#include "firmware/control/pid_tuning.hpp"
#include "tools/hil/paper_table3.hpp"

namespace tnv::hil {

namespace {

std::string line(const char* pattern, auto... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, pattern, args...);
  return buf;
}

const SweepCell* find(const std::vector<SweepCell>& cells, const std::string& scenario, fw::ControllerKind kind) {
  for (const SweepCell& c : cells)
    if (c.scenario == scenario && c.controller == kind) return &c;
  return nullptr;
}

nlohmann::json model_json(const fw::AxisModel& m) {
  return {{"A", {{m.A(0, 0), m.A(0, 1)}, {m.A(1, 0), m.A(1, 1)}}}, {"B", {m.B(0), m.B(1)}}};
}

}  // namespace

nlohmann::json results_json(const std::vector<SweepCell>& cells, int seeds) {
  nlohmann::json rows = nlohmann::json::array();
  for (const SweepCell& c : cells) {
    nlohmann::json row = {{"scenario", c.scenario},
                          {"controller", fw::to_string(c.controller)},
                          {"max_um", c.averaged.max_um},
                          {"mean_um", c.averaged.mean_um},
                          {"std_um", c.averaged.std_um},
                          {"seeds", seeds}};
    // The truth beside the encoder-measured score (tool point = table + structural mode).
    row["true_table"] = {{"max_um", c.true_table_averaged.max_um},
                         {"mean_um", c.true_table_averaged.mean_um},
                         {"std_um", c.true_table_averaged.std_um}};
    row["true_tool"] = {{"max_um", c.true_tool_averaged.max_um},
                        {"mean_um", c.true_tool_averaged.mean_um},
                        {"std_um", c.true_tool_averaged.std_um}};
    if (!c.error.empty()) row["error"] = c.error;
    if (const auto paper = paper_row(c.scenario)) {
      const ContourStats& p = paper->of(c.controller);
      row["paper"] = {{"max_um", p.max_um}, {"mean_um", p.mean_um}, {"std_um", p.std_um}};
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

nlohmann::json pid_gains_json(const fw::FirmwareConfig& config) {
  nlohmann::json out;
  for (std::size_t i = 0; i < 2; ++i) {
    const fw::PidParams& p = config.axis[i].pid;
    const fw::PidTuningReport t = fw::paper_pid_tuning(hal::axis_from_index(i));
    out[hal::kAxisNames[i]] = {{"kp_per_s", p.kp},
                               {"ki_per_s2", p.ki},
                               {"kd", p.kd},
                               {"derivative_filter_s", p.derivative_filter_tf_s},
                               {"feedforward", p.feedforward},
                               {"crossover_hz", t.pid_crossover_hz},
                               {"phase_margin_deg", t.pid_phase_margin_deg},
                               {"dvsc_crossover_hz", t.dvsc_crossover_hz},
                               {"dvsc_phase_margin_deg", t.dvsc_phase_margin_deg}};
    out["rule"] = t.rule;
  }
  return out;
}

std::string pid_gains_text(const fw::FirmwareConfig& config) {
  std::string out = "PID baseline, rule: ";
  out += fw::paper_pid_tuning(hal::Axis::x).rule;
  out += '\n';
  for (std::size_t i = 0; i < 2; ++i) {
    const fw::PidParams& p = config.axis[i].pid;
    const fw::PidTuningReport t = fw::paper_pid_tuning(hal::axis_from_index(i));
    out += line("  %c: Kp = %.4g 1/s  Ki = %.4g 1/s^2  Kd = %.4g  (crossover %.2f Hz, PM %.1f deg;"
                " DVSC+DDC: %.2f Hz, PM %.1f deg)\n",
                hal::axis_upper_name(hal::axis_from_index(i)), p.kp, p.ki, p.kd, t.pid_crossover_hz, t.pid_phase_margin_deg,
                t.dvsc_crossover_hz, t.dvsc_phase_margin_deg);
  }
  return out;
}

std::string table3_text(const std::vector<SweepCell>& cells, int seeds, const fw::FirmwareConfig& config) {
  std::string out = line("S1 Table 3: contour error in um, averaged over %d encoder offsets / cutting phases\n", seeds);
  out += "                       ---------- ours ----------   --------- paper ----------\n";
  out += "scenario   controller      max     mean      std        max     mean      std\n";
  std::vector<std::string> scenarios;
  for (const SweepCell& c : cells)
    if (scenarios.empty() || scenarios.back() != c.scenario) scenarios.push_back(c.scenario);
  for (const std::string& s : scenarios) {
    for (fw::ControllerKind k : {fw::ControllerKind::pid, fw::ControllerKind::dvsc, fw::ControllerKind::rdvsc}) {
      const SweepCell* c = find(cells, s, k);
      if (!c) continue;
      out += line("%-10s %-10s %8.4f %8.4f %8.4f", s.c_str(), fw::to_string(k), c->averaged.max_um,
                  c->averaged.mean_um, c->averaged.std_um);
      if (const auto paper = paper_row(s)) {
        const ContourStats& p = paper->of(k);
        out += line("   %8.4f %8.4f %8.4f", p.max_um, p.mean_um, p.std_um);
      }
      if (!c->error.empty()) out.append("   FAILED: ").append(c->error);
      out += "\n";
    }
  }
  out += "\nRatios (ours / paper)    R/PID max      R/PID std      R/DVSC max     R/DVSC std\n";
  for (const nlohmann::json& r : table3_ratios_json(cells)) {
    const auto s = r["scenario"].get<std::string>();
    out += line("%-24s", s.c_str());
    for (const char* key : {"r_pid_max", "r_pid_std", "r_dvsc_max", "r_dvsc_std"}) {
      const double ours = r[key]["ours"].get<double>();
      if (r[key].contains("paper"))
        out += line("  %5.3f / %5.3f", ours, r[key]["paper"].get<double>());
      else
        out += line("  %5.3f        ", ours);
    }
    out += "\n";
  }
  out += '\n';
  out += pid_gains_text(config);
  return out;
}

nlohmann::json table3_ratios_json(const std::vector<SweepCell>& cells) {
  nlohmann::json out = nlohmann::json::array();
  std::vector<std::string> scenarios;
  for (const SweepCell& c : cells)
    if (scenarios.empty() || scenarios.back() != c.scenario) scenarios.push_back(c.scenario);
  for (const std::string& s : scenarios) {
    const SweepCell* pid = find(cells, s, fw::ControllerKind::pid);
    const SweepCell* dvsc = find(cells, s, fw::ControllerKind::dvsc);
    const SweepCell* rdvsc = find(cells, s, fw::ControllerKind::rdvsc);
    if (!rdvsc || !pid || !dvsc) continue;
    const auto paper = paper_row(s);
    auto ratio = [&](const SweepCell* base, double ContourStats::*field) {
      nlohmann::json r = {{"ours", rdvsc->averaged.*field / base->averaged.*field}};
      if (paper) r["paper"] = paper->rdvsc.*field / paper->of(base->controller).*field;
      return r;
    };
    out.push_back({{"scenario", s},
                   {"r_pid_max", ratio(pid, &ContourStats::max_um)},
                   {"r_pid_std", ratio(pid, &ContourStats::std_um)},
                   {"r_dvsc_max", ratio(dvsc, &ContourStats::max_um)},
                   {"r_dvsc_std", ratio(dvsc, &ContourStats::std_um)}});
  }
  return out;
}

std::string circle_text(const SweepCell& cell, int seeds) {
  std::string out = line("circle  scenario %s  controller %s  seeds %d\n", cell.scenario.c_str(),
                         fw::to_string(cell.controller), seeds);
  out += line("contour error: max %.4f um   mean %.4f um   std %.4f um\n", cell.averaged.max_um,
              cell.averaged.mean_um, cell.averaged.std_um);
  out += line("  true, table: max %.4f um   mean %.4f um   std %.4f um\n", cell.true_table_averaged.max_um,
              cell.true_table_averaged.mean_um, cell.true_table_averaged.std_um);
  out += line("  true, tool:  max %.4f um   mean %.4f um   std %.4f um\n", cell.true_tool_averaged.max_um,
              cell.true_tool_averaged.mean_um, cell.true_tool_averaged.std_um);
  if (const auto paper = paper_row(cell.scenario)) {
    const ContourStats& p = paper->of(cell.controller);
    out += line("paper (S1 Table 3): max %.4f um   mean %.4f um   std %.4f um\n", p.max_um, p.mean_um, p.std_um);
  }
  if (seeds > 1) {
    out += "per seed (max / mean / std um):\n";
    for (std::size_t i = 0; i < cell.per_seed.size(); ++i)
      out += line("  seed %zu: %.4f / %.4f / %.4f\n", i, cell.per_seed[i].max_um, cell.per_seed[i].mean_um,
                  cell.per_seed[i].std_um);
  }
  if (!cell.error.empty()) out.append("FAILED: ").append(cell.error).append("\n");
  return out;
}

nlohmann::json plant_check_json(const std::array<PlantCheckAxis, 2>& axes) {
  nlohmann::json out;
  for (std::size_t i = 0; i < 2; ++i) {
    nlohmann::json a = model_json(axes[i].identified);
    a["exact"] = model_json(axes[i].exact);
    a["paper"] = model_json(axes[i].paper);
    a["max_abs_diff_exact"] = axes[i].max_abs_diff_exact;
    out[hal::kAxisNames[i]] = std::move(a);
  }
  return out;
}

std::string plant_check_text(const std::array<PlantCheckAxis, 2>& axes) {
  std::string out = "1 ms ZOH model of the emulated axes (friction and cutting off)\n";
  out += "axis  entry     identified         exact   paper (31)\n";
  for (std::size_t i = 0; i < 2; ++i) {
    const char axis = hal::axis_upper_name(hal::axis_from_index(i));
    const PlantCheckAxis& a = axes[i];
    const char* names[] = {"A11", "A12", "A21", "A22"};
    for (int k = 0; k < 4; ++k) {
      const int r = k / 2, c = k % 2;
      out += line("%c     %-5s %12.7f  %12.7f  %10.4f\n", axis, names[k], a.identified.A(r, c), a.exact.A(r, c),
                  a.paper.A(r, c));
    }
    out += line("%c     %-5s %12.7f  %12.7f  %10.4f\n", axis, "B1", a.identified.B(0), a.exact.B(0), a.paper.B(0));
    out += line("%c     %-5s %12.7f  %12.7f  %10.4f\n", axis, "B2", a.identified.B(1), a.exact.B(1), a.paper.B(1));
    out += line("%c     max |identified - exact| = %.3g\n", axis, a.max_abs_diff_exact);
  }
  return out;
}

}  // namespace tnv::hil
