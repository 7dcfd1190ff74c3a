#pragma once
// The soak figure: per-cycle contour statistics, position error and the
// DDC's disturbance estimate at rest, over the whole run, with the 32-bit
// clock wraps marked.
#include <string_view>

#include "tools/hil/soak_run.hpp"
#include "tools/hil/svg_writer.hpp"

namespace tnv::hil {

SvgWriter soak_figure(const SoakResult& result, std::string_view scenario_name);

}  // namespace tnv::hil
