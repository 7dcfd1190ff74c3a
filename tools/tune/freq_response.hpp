#pragma once
// Frequency responses from the averaged spectra of one closed-loop
// experiment (freq_response_spectra.hpp), d the excitation at the plant
// input, u = c + d the command the plant received. With the convention of
// firmware/control/loop_analysis.hpp (L = -K P, closed loop 1 + L = 0):
//   plant   P = S_yd / S_ud            (DAC command -> encoder position)
//   open    L = -S_cd / S_ud           (loop broken at the plant input)
//   closed  T = -S_cd / S_dd = L / (1 + L)   (d -> -c: complementary sensitivity)
// Each ratio of cross spectra with d is the H1 estimate with d as the
// instrument. Coherence: the smallest squared coherence with d of the
// signals in the ratio (gamma^2_xd = |S_xd|^2 / (S_xx S_dd)), 0..1.
#include <complex>
#include <string>
#include <vector>

#include "tools/tune/freq_response_spectra.hpp"

namespace tnv::tune {

enum class LoopKind { plant, open, closed };

const char* to_string(LoopKind kind) noexcept;
// "plant", "open", "closed"; false for anything else.
bool parse_loop_kind(const std::string& text, LoopKind& out) noexcept;

struct ResponsePoint {
  double freq_hz = 0.0;
  std::complex<double> response;
  double coherence = 0.0;
};

std::vector<ResponsePoint> loop_response(const std::vector<SpectraPoint>& spectra, LoopKind kind);

double gain_db(std::complex<double> h) noexcept;
double phase_deg(std::complex<double> h) noexcept;  // (-180, 180]

}  // namespace tnv::tune
