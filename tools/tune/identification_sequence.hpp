#pragma once
// The identification sequence and the records it yields, shared by the
// HIL rig (tools/hil/tune_identify.hpp) and the CAN tool (tnvctl identify,
// tools/can/can_identify.hpp): the same excitations, cut into StepRecord /
// RampRecord the same way, so both feed identify_from_records() alike.
//
//   steps  +10, -10, +20, -20 mm/s for 0.15 s, then 0.2 s at u = 0
//   ramps  +-2 mm/s^2 t (|u| <= 10 mm/s, at most 5 s) until 12 counts moved
#include <vector>

#include "firmware/compensation/excitation.hpp"
#include "tools/tune/axis_identification.hpp"

namespace tnv::tune {

std::vector<fw::ExcitationSpec> identification_steps();
std::vector<fw::ExcitationSpec> identification_ramps();

// From one excitation's per-tick series, index 0 = its first tick:
// position_mm[j] measured at tick j (before tick j's command acts),
// command_mm_s[j] the DAC-quantised command tick j applied.
// The step record keeps the drive phase (duration_s / 1 ms + 1 positions).
StepRecord step_record_from(const fw::ExcitationSpec& spec, const std::vector<double>& position_mm,
                            const std::vector<double>& command_mm_s);
// The command of the tick before the first moved reading broke the axis away.
RampRecord ramp_record_from(const std::vector<double>& position_mm, const std::vector<double>& command_mm_s);

}  // namespace tnv::tune
