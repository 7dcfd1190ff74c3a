#pragma once
// The S4 figure: seed 1 part by part as in the paper's Figs. 3 and 4
// (deflection at both positions inside/outside d0 +- 3 sigma, infeed beside
// the optimal, alpha/beta and C estimates beside the true values), plus
// the share of all seeds that made a bad part or reset P at each part.
#include <string_view>

#include "tools/hil/boring_sweep.hpp"
#include "tools/hil/svg_writer.hpp"

namespace tnv::hil {

SvgWriter boring_figure(std::string_view title, const BoringRunRequest& request, const BoringSweepResult& result);

}  // namespace tnv::hil
