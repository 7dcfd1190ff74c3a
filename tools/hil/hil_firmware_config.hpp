#pragma once
// The firmware's commissioning parameters for an emulated machine: the
// encoder resolution and DAC scale are hardware facts copied from the
// scenario; the controllers keep the model and gains they were given.
#include "emulator/scenario.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/trajectory/circle_trajectory.hpp"

namespace tnv::hil {

fw::FirmwareConfig firmware_config_for(const emu::Scenario& scenario, const fw::FirmwareConfig& base);

// What an exactly homed machine reads at physical position_mm: the grid
// point the encoder reports, in the physical frame (count - offset) * q.
// The firmware is homed with this, so the encoder grid keeps its scenario
// phase relative to the circle (the phase the seeds vary) and perfect
// tracking shows only the rounding, not a homing bias.
double homed_position_mm(const emu::Scenario& scenario, hal::Axis axis, double position_mm);

fw::CircleSpec circle_spec_for(const emu::Scenario& scenario) noexcept;

}  // namespace tnv::hil
