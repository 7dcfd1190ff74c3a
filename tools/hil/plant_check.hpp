#pragma once
// Identifies the 1 ms zero-order-hold model (A, B) of each emulated axis,
// friction and cutting off, by stepping the emulator's own sub-stepped
// plant from unit initial states and a unit input, and sets it beside the
// exact closed form and the paper's printed S1 eq. (31).
#include <array>

#include "emulator/scenario.hpp"
#include "firmware/control/axis_model.hpp"

namespace tnv::hil {

struct PlantCheckAxis {
  fw::AxisModel identified{};
  fw::AxisModel exact{};
  fw::AxisModel paper{};
  double max_abs_diff_exact = 0.0;  // identified vs exact
};

std::array<PlantCheckAxis, 2> plant_check(const emu::Scenario& scenario);

}  // namespace tnv::hil
