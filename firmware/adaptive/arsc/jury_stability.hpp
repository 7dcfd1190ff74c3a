#pragma once
// Jury's stability test for the estimated model's characteristic quartic
// z^4 + d1 z^3 + d2 z^2 + d3 z + d4 (S3 eqs. (30)-(31)). The OCR prints
// D11 = 1 - d1^2; the Jury table gives D11 = 1 - d4^2 (issue 8), which is
// what is implemented: with it the four conditions are exactly "all roots
// inside the unit circle" (tested against polynomials with known roots).
#include <array>
#include <cstdint>

namespace tnv::fw::arsc {

enum class JuryFailure : std::uint8_t {
  none = 0,
  not_finite,
  condition_i,    // |d4| < 1
  condition_ii,   // |D14| < |D11|
  condition_iii,  // |D23| < |D21|
  condition_iv,   // |D32| < |D31|
};

struct JuryResult {
  bool stable = false;
  JuryFailure failure = JuryFailure::not_finite;
};

// d = [d1, d2, d3, d4].
JuryResult jury_quartic(const std::array<double, 4>& d) noexcept;

}  // namespace tnv::fw::arsc
