#include "tools/hil/best_circle.hpp"

#include <algorithm>
#include <utility>

#include "hal/axis.hpp"

namespace tnv::hil {

fw::FirmwareConfig with_friction_feedforward(const fw::FirmwareConfig& base,
                                             const std::array<fw::FrictionFeedForward, 2>& friction) {
  fw::FirmwareConfig config = base;
  const std::array<hal::Axis, 2> plane{hal::kPlaneFirst, hal::kPlaneSecond};
  for (std::size_t i = 0; i < plane.size(); ++i) {
    fw::AxisConfig& axis = config.axis[hal::index(plane[i])];
    axis.friction = friction[i];
    axis.friction.enabled = true;
  }
  return config;
}

std::vector<BestCircleRow> run_best_circle(const BestCircleRequest& request, const fw::FirmwareConfig& best) {
  const std::size_t total = 2 * request.scenarios.size() * static_cast<std::size_t>(request.seeds);
  auto progress_with = [&](std::size_t base_done) {
    std::function<void(std::size_t, std::size_t)> p;
    if (request.progress)
      p = [&request, total, base_done](std::size_t done, std::size_t) { request.progress(base_done + done, total); };
    return p;
  };
  SweepRequest papers{request.scenarios, {fw::ControllerKind::rdvsc}, request.seeds, request.keep_seed0_trace, 0,
                      progress_with(0)};
  const std::vector<SweepCell> baseline = run_sweep(papers, fw::default_firmware_config());
  SweepRequest ours = papers;
  ours.progress = progress_with(total / 2);
  const std::vector<SweepCell> improved = run_sweep(ours, best);
  std::vector<BestCircleRow> rows;
  for (std::size_t s = 0; s < request.scenarios.size(); ++s) {
    BestCircleRow row;
    row.scenario = baseline[s].scenario;
    row.rdvsc = baseline[s].averaged;
    row.best = improved[s].averaged;
    row.error = !baseline[s].error.empty() ? baseline[s].error : improved[s].error;
    row.rdvsc_cell = baseline[s];
    row.best_cell = improved[s];
    rows.push_back(std::move(row));
  }
  return rows;
}

BestConfigDesign design_best_config(const emu::Scenario& table, const BestConfigChoice& choice) {
  BestConfigDesign out;
  // Identify with the spindle off: the cutting load opposes every excitation move and would bias f_c.
  emu::Scenario idle = table;
  idle.cutting.enabled = false;
  idle.milling.enabled = false;
  for (std::size_t i = 0; i < 2; ++i) {
    const char* axis_name = hal::kAxisNames[i];
    const tune::AxisIdentification& id = out.identified[i] = identify_axis_on_emulator(idle, hal::axis_from_index(i));
    tune::AxisDesign& d = out.designs[i] = tune::design_axis(id);
    if (!d.ok) {
      out.error = std::string("axis ") + axis_name + ": " + d.error;
      return out;
    }
    d.friction.fraction = choice.ff_fraction;
    // stribeck: the whole identified model (f_s and the assumed v_s) fed forward.
    if (choice.ff == BestFeedForward::stribeck) d.friction.stiction_mm_s = std::max(id.stiction_mm_s, id.coulomb_mm_s);
    if (choice.ff == BestFeedForward::off) d.friction.enabled = false;
    if (choice.observer_sigma_v_mm_s != tune::kObserverSpeedNoise_mm_s ||
        choice.observer_sigma_d_mm_s != tune::kObserverDisturbanceNoise_mm_s) {
      d.observer_noise.speed_mm_s = choice.observer_sigma_v_mm_s;
      d.observer_noise.disturbance_mm_s = choice.observer_sigma_d_mm_s;
      const fw::ObserverDesign obs = tune::design_observer(d.model, d.observer_noise);
      if (!obs.ok) {
        out.bad_input = true;
        out.error = std::string("axis ") + axis_name + ": no stable observer for these noise levels";
        return out;
      }
      d.observer.gain_position = obs.params.gain_position;
      d.observer.gain_speed_1_s = obs.params.gain_speed_1_s;
      d.observer.gain_disturbance_1_s = obs.params.gain_disturbance_1_s;
    }
    if (!choice.observer_friction) d.observer.friction_mm_s = 0.0;
    d.observer.enabled = choice.observer != BestObserverUse::off;
    d.observer.use_position = choice.observer == BestObserverUse::position;
  }
  out.config = tune::apply_designs(fw::default_firmware_config(), out.designs[0], out.designs[1]);
  if (choice.gains == BestGains::papers) {
    out.config = fw::default_firmware_config();
    for (std::size_t i = 0; i < 2; ++i) {
      out.config.axis[i].friction = out.designs[i].friction;
      // The observer is built on the identified model; the papers' config keeps the paper model.
      out.config.axis[i].observer = out.designs[i].observer;
    }
  }
  if (const fw::ConfigError e = fw::validate(out.config); !e.ok()) {
    out.bad_input = true;
    out.error = std::string(e.section) + ": " + e.field + ": " + e.reason;
    return out;
  }
  out.ok = true;
  return out;
}

fw::FirmwareConfig without_observer(const fw::FirmwareConfig& best) {
  fw::FirmwareConfig config = best;
  for (fw::AxisConfig& a : config.axis) a.observer.enabled = false;
  return config;
}

TableCheckRow run_table_check(const TableCheckRequest& request, const fw::FirmwareConfig& best) {
  const std::size_t per_config = static_cast<std::size_t>(request.seeds);
  const std::array<fw::FirmwareConfig, 3> configs{fw::default_firmware_config(), best, without_observer(best)};
  const std::array<const char*, 3> config_names{"papers' R-DVSC+DDC", "best", "best, observer off"};
  std::array<SweepCell, 3> cells{};
  for (std::size_t k = 0; k < configs.size(); ++k) {
    std::function<void(std::size_t, std::size_t)> report;
    if (request.progress)
      report = [&request, per_config, k](std::size_t done, std::size_t) {
        request.progress(k * per_config + done, 3 * per_config);
      };
    const SweepRequest sweep{{request.table}, {fw::ControllerKind::rdvsc}, request.seeds, request.keep_seed0_trace, 0,
                             report};
    std::vector<SweepCell> got = run_sweep(sweep, configs[k]);
    if (got.empty()) {
      cells[k].scenario = request.table.name;
      cells[k].error = "no run";
    } else {
      cells[k] = std::move(got.front());
    }
  }
  TableCheckRow row;
  row.scenario = request.table.name;
  row.rdvsc = cells[0].averaged;
  row.best = cells[1].averaged;
  row.observer_off = cells[2].averaged;
  for (std::size_t k = 0; k < cells.size() && row.error.empty(); ++k)
    if (!cells[k].error.empty()) row.error = std::string(config_names[k]) + ": " + cells[k].error;
  row.rdvsc_cell = std::move(cells[0]);
  row.best_cell = std::move(cells[1]);
  row.observer_off_cell = std::move(cells[2]);
  return row;
}

}  // namespace tnv::hil
