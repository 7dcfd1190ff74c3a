#include "tools/hil/best_circle.hpp"

#include <utility>

namespace tnv::hil {

fw::FirmwareConfig with_friction_feedforward(const fw::FirmwareConfig& base,
                                             const std::array<fw::FrictionFeedForward, 2>& friction) {
  fw::FirmwareConfig config = base;
  for (std::size_t i = 0; i < config.axis.size(); ++i) {
    config.axis[i].friction = friction[i];
    config.axis[i].friction.enabled = true;
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

}  // namespace tnv::hil
