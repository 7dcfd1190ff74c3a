#pragma once
// Stability margins and bandwidth read off a measured (or sampled model)
// frequency response, the points in rising frequency. Between two points
// the gain (dB) and the unwrapped phase are interpolated linearly in
// log frequency.
//   crossover: the highest |L| = 1 crossing; phase margin 180 + arg L there
//              (the smallest over all crossings, as loop_analysis.hpp);
//   gain margin: -|L| in dB where the unwrapped phase crosses -180 + k 360
//              with |L| < 1 (the smallest); +inf if the points show none;
//   bandwidth: the first frequency where |T| falls 3 dB below its value at
//              the lowest point (NaN if it never does).
#include <vector>

#include "tools/tune/freq_response.hpp"

namespace tnv::tune {

struct BodeMargins {
  bool crossover_found = false;
  double crossover_hz = 0.0;
  double phase_margin_deg = 0.0;
  double gain_margin_db = 0.0;          // +inf: no phase crossing below |L| = 1 in the points
  double phase_crossover_hz = 0.0;      // where gain_margin_db was read (0 if none)
};

BodeMargins margins_from_points(const std::vector<ResponsePoint>& open_loop);

// The -3 dB bandwidth of a closed-loop response (NaN if not reached).
double bandwidth_hz(const std::vector<ResponsePoint>& closed_loop);

// The closed loop T = L / (1 + L) of each open-loop point (coherence kept).
std::vector<ResponsePoint> closed_from_open(const std::vector<ResponsePoint>& open_loop);

}  // namespace tnv::tune
