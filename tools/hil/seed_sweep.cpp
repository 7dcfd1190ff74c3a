#include "tools/hil/seed_sweep.hpp"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>

#include "tools/hil/seeded_scenario.hpp"

namespace tnv::hil {

std::vector<SweepCell> run_sweep(const SweepRequest& request, const fw::FirmwareConfig& config) {
  const std::size_t n_controllers = request.controllers.size();
  const std::size_t n_seeds = static_cast<std::size_t>(std::max(1, request.seeds));
  std::vector<SweepCell> cells(request.scenarios.size() * n_controllers);
  for (std::size_t s = 0; s < request.scenarios.size(); ++s) {
    for (std::size_t c = 0; c < n_controllers; ++c) {
      SweepCell& cell = cells[s * n_controllers + c];
      cell.scenario = request.scenarios[s].name;
      cell.controller = request.controllers[c];
      cell.per_seed.resize(n_seeds);
      cell.true_table_per_seed.resize(n_seeds);
      cell.true_tool_per_seed.resize(n_seeds);
    }
  }
  const std::size_t total = cells.size() * n_seeds;
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> done{0};
  std::mutex error_mutex;

  auto worker = [&] {
    for (std::size_t job = next++; job < total; job = next++) {
      const std::size_t cell_index = job / n_seeds;
      const std::size_t seed = job % n_seeds;
      SweepCell& cell = cells[cell_index];
      const emu::Scenario& base = request.scenarios[cell_index / n_controllers];
      CircleRunOptions options;
      options.keep_trace = request.keep_seed0_trace && seed == 0;
      CircleRunResult r = run_circle(seeded(base, static_cast<int>(seed)), config, cell.controller, options);
      cell.per_seed[seed] = r.stats;
      cell.true_table_per_seed[seed] = r.true_table_stats;
      cell.true_tool_per_seed[seed] = r.true_tool_stats;
      if (!r.completed) {
        std::lock_guard lock(error_mutex);
        if (cell.error.empty()) cell.error = "seed " + std::to_string(seed) + ": " + r.error;
      }
      if (seed == 0) cell.seed0 = std::move(r);
      const std::size_t finished = ++done;
      if (request.progress) request.progress(finished, total);
    }
  };

  unsigned threads = request.threads != 0 ? request.threads : std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, total));
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < threads; ++i) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();

  for (SweepCell& cell : cells) {
    cell.averaged = average(cell.per_seed);
    cell.true_table_averaged = average(cell.true_table_per_seed);
    cell.true_tool_averaged = average(cell.true_tool_per_seed);
  }
  return cells;
}

}  // namespace tnv::hil
