#pragma once
// Plant identification on the HIL rig: the identification sequence
// (tools/tune/identification_sequence.hpp) run by the real firmware on the
// emulated board and table of a scenario, its records fitted by the tuning
// library (tools/tune/axis_identification.hpp).
#include <string>

#include "emulator/scenario.hpp"
#include "hal/axis.hpp"
#include "tools/tune/axis_identification.hpp"
#include "tools/tune/mode_fit.hpp"

namespace tnv::hil {

tune::AxisIdentification identify_axis_on_emulator(const emu::Scenario& scenario, hal::Axis axis);

// Two text lines for `tnv-hil identify`: the fit beside the scenario's true
// mode (true_hz == 0: the scenario has none).
std::string mode_fit_text(const tune::ModeFit& fit, double true_hz, double true_zeta);

}  // namespace tnv::hil
