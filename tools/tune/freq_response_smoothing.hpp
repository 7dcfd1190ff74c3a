#pragma once
// A measured frequency response smoothed across neighbouring points before
// margins are read off it (docs/frequency-response.md): with the encoder's
// quantisation decorrelated from the excitation (the carrier), what is left
// near the phase crossover is noise of low coherence, and reading a margin
// by interpolating between two such points takes their noise in whole.
//
// At each point: a weighted least-squares quadratic in log f of the gain
// (dB) and of the unwrapped phase over the points within half_window
// indices each side, evaluated there. Weights gamma^2 / (1 - gamma^2), the
// inverse of an H1 estimate's relative variance (up to the number of
// averages, the same for every point). The coherence is kept.
#include <vector>

#include "tools/tune/freq_response.hpp"

namespace tnv::tune {

// half_window 0, or fewer than 3 points: the points unchanged. Windows
// are cut at the ends; a window of 2 points fits a line.
std::vector<ResponsePoint> smoothed_response(const std::vector<ResponsePoint>& points, int half_window);

}  // namespace tnv::tune
