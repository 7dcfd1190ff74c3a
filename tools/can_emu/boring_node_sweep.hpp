#pragma once
// tnv-hil boring's default run: every part of every seed through the
// emulated node (EmulatedBus: the real firmware on the emulated board,
// behind the virtual CAN wire) with BoringNodeLink. Nothing is saved: the
// node's parameter file is a temporary path that is never written.
#include <string>

#include "tools/hil/boring_sweep.hpp"

namespace tnv::can_host {

// Throws std::invalid_argument as run_boring_sweep(); `error` is set (and
// the result empty) when the emulated node cannot be made.
hil::BoringSweepResult run_boring_sweep_on_emulated_node(const hil::BoringRunRequest& request, int seeds,
                                                         const hil::BoringProgress& progress, std::string& error);

}  // namespace tnv::can_host
