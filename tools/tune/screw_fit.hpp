#pragma once
// What a lead-error measurement (gauge_point.hpp) says about the screw, in
// the firmware's compensation terms (firmware/compensation/
// screw_compensation.hpp): the backlash b, the cumulative lead error c and
// the per-turn table. Least squares on the reading's error against the
// encoder position p, approach direction d = +-1:
//
//   table - p = c p - d b / 2 + k + sum_h=1..4 (s_h sin(2 pi h p / P) + c_h cos(2 pi h p / P))
//
// (k: the reference's zero). The per-turn table is the harmonic part at
// the table's 16 points. Four harmonics: a 16-point table cannot hold more
// than the eighth, and a thread's error is mostly the first (eccentricity)
// and the second.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "firmware/compensation/screw_compensation.hpp"
#include "tools/tune/gauge_point.hpp"

namespace tnv::tune {

struct ScrewFit {
  double backlash_um = 0.0;
  double lead_um_per_m = 0.0;
  double turn_period_mm = 10.0;
  std::array<double, fw::kTurnErrorPoints> turn_error_um{};
  std::size_t points = 0;
  double span_mm = 0.0;
  double error_rms_um = 0.0;     // the reading's error about its mean, before the fit
  double residual_rms_um = 0.0;  // what the model leaves
  double residual_max_um = 0.0;
};

// nullopt with `error` when the points cannot determine the model: fewer
// than 8 per direction, one direction only, a span shorter than one period
// (the harmonics and the lead error cannot be told apart), or a bad period.
std::optional<ScrewFit> fit_screw(const std::vector<GaugePoint>& points, double turn_period_mm, std::string& error);

// The fit as the firmware's compensation (backlash_rate_mm_s from `base`).
fw::ScrewCompensation to_compensation(const ScrewFit& fit, const fw::ScrewCompensation& base);

// The fitted model's reading error (um) at p approached from d, without the zero k.
double fitted_error_um(const ScrewFit& fit, double position_mm, int direction);

}  // namespace tnv::tune
