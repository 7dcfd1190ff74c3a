#pragma once
// Seed-averaging: the max contour error moves by about +-15% with the
// encoder phase alone (reference plant), so results are averaged over
// encoder offsets and cutting phases. Seed 0 is the scenario as written;
// seed k adds a low-discrepancy (golden-ratio) shift to the fractional
// encoder offsets and to the cutting phase.
#include "emulator/scenario.hpp"

namespace tnv::hil {

emu::Scenario seeded(const emu::Scenario& base, int seed) noexcept;

}  // namespace tnv::hil
