#pragma once
// One ARSC tick-study run as JSON: what `tnv-hil arsc tick --json` prints
// and the names an `arsc tick` campaign's rows give its results.
#include <nlohmann/json.hpp>

#include "tools/hil/arsc_tick_study.hpp"

namespace tnv::hil {

nlohmann::json tick_study_json(const TickStudyResult& result);

}  // namespace tnv::hil
