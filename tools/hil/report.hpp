#pragma once
// Human tables and machine-readable JSON for tnv-hil results.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "firmware/tick/firmware_config.hpp"
#include "tools/hil/plant_check.hpp"
#include "tools/hil/seed_sweep.hpp"
#include "tools/score/contour_stats.hpp"
#include "tools/score/score_json.hpp"

namespace tnv::hil {

// {"scenario","controller","max_um","mean_um","std_um","seeds"} per cell.
nlohmann::json results_json(const std::vector<SweepCell>& cells, int seeds);
// {"x":{"kp","ki","kd",...},"y":{...},"rule":...} from the config in use.
nlohmann::json pid_gains_json(const fw::FirmwareConfig& config);
std::string pid_gains_text(const fw::FirmwareConfig& config);

// Our Table 3 beside the paper's, with the R/PID and R/DVSC ratios.
std::string table3_text(const std::vector<SweepCell>& cells, int seeds, const fw::FirmwareConfig& config);
nlohmann::json table3_ratios_json(const std::vector<SweepCell>& cells);

std::string circle_text(const SweepCell& cell, int seeds);

nlohmann::json plant_check_json(const std::array<PlantCheckAxis, 2>& axes);
std::string plant_check_text(const std::array<PlantCheckAxis, 2>& axes);

}  // namespace tnv::hil
