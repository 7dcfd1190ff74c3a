#pragma once
// S4 in the loop: the firmware's infeed planner plans every part (on the
// node over CAN, or called in this process: boring_planner_link.hpp), the
// emulator's BoringProcess cuts it and its gauge measures it; parts are
// judged on the TRUE deflection at the measuring positions (bad = outside
// d0 +- 3 sigma at either position). Seeds only change the gauge noise.
#include <cstdint>
#include <string>
#include <vector>

#include "emulator/boring_process.hpp"
#include "emulator/scenario.hpp"
#include "firmware/adaptive/boring/boring_planner_params.hpp"
#include "tools/score/boring_planner_link.hpp"

namespace tnv::hil {

struct BoringRunRequest {
  fw::BoringPlannerParams planner{};         // its sigma_d_mm is what the planner believes
  double process_sigma_mm = 0.016231;        // gauge noise of the emulated process
  double band_sigma_mm = 0.016231;           // bad part: true d outside d0 +- 3 band_sigma_mm
  int parts = 30;
  std::vector<int> change_at = {11, 21};     // part numbers where sets 2 and 3 take over (0-2 entries)
  std::vector<double> positions_mm = {40.0, 310.0};  // measuring overhangs, in order
  // A bench's bore gauge on top of process_sigma_mm (boring --scenario: [noise] bore_gauge_*):
  // repeatability and reading step on the diametral bore error; 0 = an exact gauge. Its noise
  // stream is seeded from gauge_seed and the run's seed.
  double gauge_noise_mm_rms = 0.0;
  double gauge_resolution_mm = 0.0;
  std::uint64_t gauge_seed = 0;
};

// The paper's setting for sigma_d and alpha0 (Figs. 3, 4): planner and
// process share sigma_d; the band is d0 +- 3 sigma_d.
BoringRunRequest paper_boring_request(double sigma_d_mm, double alpha0);

// `request` measured with the scenario's bore gauge ([noise] bore_gauge_um_rms,
// bore_gauge_resolution_um, seed). The rest of a scenario does not reach a
// part's deflection (docs/robustness.md, "What the bench does").
BoringRunRequest with_scenario_gauge(BoringRunRequest request, const emu::Scenario& scenario);

// "" if valid, else "field: reason" (the planner params, the process, the
// parts count, the change points and the positions).
std::string validate_boring_request(const BoringRunRequest& request);

struct BoringPositionRecord {
  double overhang_mm = 0.0;
  double infeed_mm_rev = 0.0;          // what the planner commanded
  double optimal_infeed_mm_rev = 0.0;  // eq. (3) with the true set
  double true_deflection_mm = 0.0;
  double measured_deflection_mm = 0.0; // from the gauge (as the planner received it) via eq. (11)
  bool infeed_limited = false;
  // On the machine (tools/can_emu/boring_machine_run.hpp): the infeed and
  // overhang with which the bar really passed this gauge depth; in process
  // the commanded ones.
  double cut_infeed_mm_rev = 0.0;
  double cut_overhang_mm = 0.0;
};

struct BoringPartRecord {
  int part = 0;
  // On the machine: the extremes of the noise-free radius error d - d0 along the pass (0 in process).
  double pass_min_error_mm = 0.0, pass_max_error_mm = 0.0;
  double true_c_mm = 0.0, true_alpha = 0.0, true_beta = 0.0;
  std::vector<BoringPositionRecord> positions;
  double c_hat_mm = 0.0, alpha_hat = 0.0, beta_hat = 0.0;  // after this part's update
  bool bad = false;      // true deflection out of band at any position
  bool reset = false;    // variance perturbation during this part
  int resets = 0;        // how many (more than one only with reset_after < 3)
  int out_of_band = 0;   // measured values out of band
};

struct BoringRunResult {
  std::uint64_t seed = 0;
  std::vector<BoringPartRecord> parts;
  int bad_parts = 0;          // parts 1..N (part 1, cut at S0, included)
  int resets = 0;
  double deflection_rms_mm = 0.0;  // true d - d0 over parts 2..N, all positions
  std::string error;          // the planner refused a part (should never happen)
};

// A gauged part into its run: judged (bad = its true deflection outside
// d0 +- band_mm at any position), the planner's report of it (its reset, the
// estimates after it, the resets so far) and the bad-part count. False, with
// result.error naming the part, when the planner refused its readings.
bool add_gauged_part(BoringRunResult& result, BoringPartRecord rec, const BoringLinkPart& report, double d0_mm,
                     double band_mm);
// The rms of the true d - d0 over parts 2..N, every position, of the parts added.
double deflection_rms_mm(const BoringRunResult& result, double d0_mm);

// Throws std::invalid_argument when validate_boring_request() fails. The
// link is started afresh (a planner that has learned nothing).
BoringRunResult run_boring(const BoringRunRequest& request, std::uint64_t seed, BoringPlannerLink& planner);
// The same with the planner in this process at the node's resolution
// (BoringDirectLink): the node's numbers, without a node.
BoringRunResult run_boring(const BoringRunRequest& request, std::uint64_t seed);

}  // namespace tnv::hil
