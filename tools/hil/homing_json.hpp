#pragma once
// One homing's JSON, as `tnv-hil homing --json` lists it under "runs" and
// a `homing` campaign's rows name their results.
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "hal/axis.hpp"
#include "tools/hil/homing_run.hpp"

namespace tnv::hil {

nlohmann::json homing_seed_json(const HomingSeedResult& result);

// The key of a per-axis field: `pattern` with its '*' replaced by the
// axis' name ("home_error_*_um", y -> "home_error_y_um").
std::string axis_key(std::string_view pattern, hal::Axis axis);

// The per-axis keys of homing_seed_json, each pattern over every axis in
// list order: where a seed started (power_up_offset_<axis>_mm, then
// offset_counts_<axis>) and what it measured (home_error_<axis>_um, then
// reading_error_<axis>_um).
std::vector<std::string> homing_start_keys();
std::vector<std::string> homing_error_keys();

}  // namespace tnv::hil
