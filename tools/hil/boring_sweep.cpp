#include "tools/hil/boring_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tools/hil/boring_direct_link.hpp"

namespace tnv::hil {

namespace {

std::vector<BoringSegmentStats> segment_bounds(const BoringRunRequest& r) {
  std::vector<int> starts = {1, 2};
  for (int c : r.change_at) starts.push_back(c);
  std::vector<BoringSegmentStats> out;
  for (std::size_t i = 0; i < starts.size(); ++i) {
    const int first = starts[i];
    const int last = std::min(i + 1 < starts.size() ? starts[i + 1] - 1 : r.parts, r.parts);
    if (first > r.parts || last < first) continue;
    BoringSegmentStats s;
    s.first_part = first;
    s.last_part = last;
    out.push_back(s);
  }
  return out;
}

}  // namespace

BoringSweepResult run_boring_sweep(const BoringRunRequest& request, int seeds, const BoringProgress& progress) {
  BoringDirectLink planner;
  return run_boring_sweep(request, seeds, planner, progress);
}

BoringSweepResult run_boring_sweep(const BoringRunRequest& request, int seeds, BoringPlannerLink& planner,
                                   const BoringProgress& progress) {
  const BoringSeedRun run_seed = [&](std::uint64_t seed) { return run_boring(request, seed, planner); };
  return run_boring_sweep(request, seeds, planner.describe(), run_seed, progress);
}

BoringSweepResult run_boring_sweep(const BoringRunRequest& request, int seeds, const std::string& planner,
                                   const BoringSeedRun& run_seed, const BoringProgress& progress,
                                   std::uint64_t first_seed) {
  if (seeds < 1) throw std::invalid_argument("seeds: must be >= 1");
  if (first_seed < 1) throw std::invalid_argument("first_seed: must be >= 1");
  if (const std::string error = validate_boring_request(request); !error.empty())
    throw std::invalid_argument(error);
  BoringSweepResult out;
  out.planner = planner;
  out.seeds = seeds;
  out.first_seed = first_seed;
  const auto parts = static_cast<std::size_t>(request.parts);
  out.bad_fraction_by_part.assign(parts, 0.0);
  out.reset_fraction_by_part.assign(parts, 0.0);
  out.segments = segment_bounds(request);
  for (BoringSegmentStats& s : out.segments) s.bad_parts_min = request.parts;
  const double n = seeds;
  for (int k = 1; k <= seeds; ++k) {
    const std::uint64_t seed = first_seed + static_cast<std::uint64_t>(k - 1);
    BoringRunResult run = run_seed(seed);
    if (!run.error.empty() && out.error.empty()) out.error = "seed " + std::to_string(seed) + ": " + run.error;
    out.bad_parts_per_seed.push_back(run.bad_parts);
    out.resets_per_seed.push_back(run.resets);
    out.bad_parts_mean += run.bad_parts / n;
    out.bad_parts_max = std::max(out.bad_parts_max, run.bad_parts);
    out.resets_mean += run.resets / n;
    out.deflection_rms_mean_mm += run.deflection_rms_mm / n;
    for (const BoringPartRecord& p : run.parts) {
      const auto i = static_cast<std::size_t>(p.part - 1);
      out.bad_fraction_by_part[i] += p.bad ? 1.0 / n : 0.0;
      out.reset_fraction_by_part[i] += p.reset ? 1.0 / n : 0.0;
    }
    for (BoringSegmentStats& s : out.segments) {
      int bad = 0;
      int resets = 0;
      for (const BoringPartRecord& p : run.parts) {
        if (p.part < s.first_part || p.part > s.last_part) continue;
        bad += p.bad ? 1 : 0;
        resets += p.resets;
      }
      s.bad_parts_mean += bad / n;
      s.bad_parts_min = std::min(s.bad_parts_min, bad);
      s.bad_parts_max = std::max(s.bad_parts_max, bad);
      s.resets_mean += resets / n;
      s.seeds_without_bad += bad == 0 ? 1.0 / n : 0.0;
      s.seeds_without_reset += resets == 0 ? 1.0 / n : 0.0;
      s.seeds_with_one_reset += resets == 1 ? 1.0 / n : 0.0;
      if (const auto last = static_cast<std::size_t>(s.last_part - 1); last < run.parts.size()) {
        const BoringPartRecord& p = run.parts[last];
        const double ec = p.c_hat_mm / p.true_c_mm - 1.0;
        const double ea = p.alpha_hat - p.true_alpha;
        const double eb = p.beta_hat - p.true_beta;
        s.c_rel_error_end += ec / n;
        s.alpha_error_end += ea / n;
        s.beta_error_end += eb / n;
        s.c_rel_abs_error_end += std::fabs(ec) / n;
        s.alpha_abs_error_end += std::fabs(ea) / n;
        s.beta_abs_error_end += std::fabs(eb) / n;
      }
    }
    if (k == 1) out.seed1 = std::move(run);
    if (progress) progress(static_cast<std::size_t>(k), static_cast<std::size_t>(seeds));
  }
  return out;
}

}  // namespace tnv::hil
