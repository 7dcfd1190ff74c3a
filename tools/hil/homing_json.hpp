#pragma once
// One homing's JSON, as `tnv-hil homing --json` lists it under "runs" and
// a `homing` campaign's rows name their results.
#include <nlohmann/json.hpp>

#include "tools/hil/homing_run.hpp"

namespace tnv::hil {

nlohmann::json homing_seed_json(const HomingSeedResult& result);

}  // namespace tnv::hil
