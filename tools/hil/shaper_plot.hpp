#pragma once
// Figures of the input shaper: sensitivity curves (S2 Fig. 3-4 style), the
// residual left at the design frequency by rounding, splitting and the
// exact grid taps, and HIL move / jog traces at the tool point.
#include <string>
#include <vector>

#include "firmware/shaper/shaper_design.hpp"
#include "tools/hil/shaper_jog_run.hpp"
#include "tools/hil/shaper_move_compare.hpp"
#include "tools/hil/svg_writer.hpp"

namespace tnv::hil {

// Residual vibration (%) vs actual / design frequency for the five types
// designed like `spec` (the spec's type drawn heavy), and the spec's
// shaper under actual damping 0 .. 0.2; with a second mode, also the
// spec's shaper against actual frequency in Hz over both modes.
SvgWriter shaper_sensitivity_figure(const fw::ShaperSpec& spec);

// For each type: residual (%) left at the design frequency, 5-200 Hz, by
// rounding, splitting and the exact grid taps (log scale).
SvgWriter grid_method_figure(const std::vector<fw::ShaperType>& types, double zeta);

// Seed 0 of a comparison (needs its traces): positions, tool error, zoom.
SvgWriter move_figure(const std::string& title, const MoveComparison& comparison);

// A jog stream unshaped and shaped: references and tool error per axis.
SvgWriter jog_figure(const std::string& title, const JogRunResult& unshaped, const JogRunResult& shaped);

}  // namespace tnv::hil
