#include "tools/hil/plant_check.hpp"

#include <algorithm>
#include <cmath>

#include "emulator/axis_plant.hpp"
#include "emulator/substep_timing.hpp"
#include "tools/hil/hil_rig.hpp"

namespace tnv::hil {

namespace {

// Friction off: the linear plant whose ZOH model is being identified.
emu::AxisPlant linear_plant(const emu::AxisPlantParams& params) {
  emu::AxisPlantParams p = params;
  p.coulomb_mm_s = 0.0;
  p.stiction_mm_s = 0.0;
  return emu::AxisPlant(p);
}

std::array<double, 2> one_period(const emu::AxisPlantParams& params, double p0_mm, double v0_mm_s, double u_mm_s) {
  emu::AxisPlant plant = linear_plant(params);
  plant.set_state(p0_mm, v0_mm_s);
  const auto substeps = static_cast<int>(std::llround(kTickPeriodS / emu::kSubstep_s));
  for (int i = 0; i < substeps; ++i) plant.step(u_mm_s, 0.0);
  return {plant.position_mm(), plant.speed_mm_s()};
}

}  // namespace

std::array<PlantCheckAxis, 2> plant_check(const emu::Scenario& scenario) {
  std::array<PlantCheckAxis, 2> out{};
  for (std::size_t i = 0; i < 2; ++i) {
    const emu::AxisPlantParams& params = scenario.plant[i];
    PlantCheckAxis& axis = out[i];
    const auto col_p = one_period(params, 1.0, 0.0, 0.0);
    const auto col_v = one_period(params, 0.0, 1.0, 0.0);
    const auto col_u = one_period(params, 0.0, 0.0, 1.0);
    axis.identified.A << col_p[0], col_v[0], col_p[1], col_v[1];
    axis.identified.B << col_u[0], col_u[1];
    axis.exact = fw::zoh_axis_model(params.tau_s, params.gain, kTickPeriodS);
    axis.paper = fw::paper_axis_model(hal::axis_from_index(i));
    axis.max_abs_diff_exact = std::max((axis.identified.A - axis.exact.A).cwiseAbs().maxCoeff(),
                                       (axis.identified.B - axis.exact.B).cwiseAbs().maxCoeff());
  }
  return out;
}

}  // namespace tnv::hil
