#include "tools/hil/shaper_move_compare.hpp"

#include <algorithm>
#include <limits>

#include "tools/hil/seeded_scenario.hpp"

namespace tnv::hil {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

constexpr double kNever = std::numeric_limits<double>::infinity();

std::optional<double> median_settling(const std::vector<std::optional<double>>& v) {
  std::vector<double> x;
  for (const auto& s : v) x.push_back(s.value_or(kNever));
  const double m = median(x);
  if (m == kNever) return std::nullopt;
  return m;
}

}  // namespace

double MovePair::residual_ratio() const noexcept {
  return unshaped.residual_pp_um > 0.0 ? shaped.residual_pp_um / unshaped.residual_pp_um : kNever;
}

std::optional<double> MovePair::settling_ratio() const noexcept {
  if (!shaped.settling_s) return std::nullopt;
  const double unshaped_s = unshaped.settling_s.value_or(kNever);
  return unshaped_s / std::max(*shaped.settling_s, 1e-3);
}

MoveComparison compare_move(const MoveRunRequest& request, const fw::FirmwareConfig& base_config, int seeds) {
  MoveComparison c;
  std::vector<double> residual_ratios, settling_ratios, unshaped_um, shaped_um;
  std::vector<std::optional<double>> unshaped_s, shaped_s;
  for (int seed = 0; seed < std::max(seeds, 1); ++seed) {
    MoveRunRequest r = request;
    r.scenario = seeded(request.scenario, seed);
    r.keep_trace = request.keep_trace && seed == 0;
    MovePair p;
    p.seed = seed;
    p.shaped = run_move(r, base_config);
    r.shaper.reset();
    p.unshaped = run_move(r, base_config);
    for (const MoveRunResult* run : {&p.unshaped, &p.shaped})
      if (!run->completed && c.error.empty())
        c.error = "seed " + std::to_string(seed) + (run == &p.shaped ? " shaped: " : " unshaped: ") + run->error;
    if (p.unshaped.completed && p.shaped.completed) {
      residual_ratios.push_back(p.residual_ratio());
      settling_ratios.push_back(p.settling_ratio().value_or(0.0));
      unshaped_um.push_back(p.unshaped.residual_pp_um);
      shaped_um.push_back(p.shaped.residual_pp_um);
      unshaped_s.push_back(p.unshaped.settling_s);
      shaped_s.push_back(p.shaped.settling_s);
    }
    c.pairs.push_back(std::move(p));
  }
  c.median_residual_ratio = median(residual_ratios);
  c.worst_residual_ratio =
      residual_ratios.empty() ? 0.0 : *std::max_element(residual_ratios.begin(), residual_ratios.end());
  c.median_settling_ratio = median(settling_ratios);
  c.median_unshaped_residual_um = median(unshaped_um);
  c.median_shaped_residual_um = median(shaped_um);
  c.median_unshaped_settling_s = median_settling(unshaped_s);
  c.median_shaped_settling_s = median_settling(shaped_s);
  return c;
}

}  // namespace tnv::hil
