#pragma once
// The verdict and the JSON of one injected fault case (tnv-hil faults and
// a `faults` campaign's rows): met when the expected reason was latched
// with the board's outputs safe right after the latching tick (or, for a
// tolerated fault, nothing latched and the outputs live throughout).
#include <array>
#include <cstdint>

#include <nlohmann/json.hpp>

#include "hal/axis.hpp"
#include "tools/hil/fault_run.hpp"

namespace tnv::hil {

// Every axis' servopack command at zero (mm/s per axis, by hal::index).
bool every_command_zero(const std::array<double, hal::kAxisCount>& command_mm_s) noexcept;

// `mid_code`: the DAC's mid-scale register value (zero command).
bool fault_case_met(const FaultCase& fault_case, const FaultObservation& observation, std::uint32_t mid_code);

// What the firmware latched ("none" if nothing), as the report names it.
const char* latched_text(const FaultObservation& observation) noexcept;

// One case's row of `tnv-hil faults --json`.
nlohmann::json fault_case_json(const FaultCase& fault_case, const FaultObservation& observation, bool met);

}  // namespace tnv::hil
