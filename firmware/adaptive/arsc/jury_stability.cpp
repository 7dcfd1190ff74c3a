#include "firmware/adaptive/arsc/jury_stability.hpp"

#include <cmath>

namespace tnv::fw::arsc {

JuryResult jury_quartic(const std::array<double, 4>& d) noexcept {
  const double d1 = d[0], d2 = d[1], d3 = d[2], d4 = d[3];
  if (!(std::isfinite(d1) && std::isfinite(d2) && std::isfinite(d3) && std::isfinite(d4)))
    return {false, JuryFailure::not_finite};
  if (!(std::fabs(d4) < 1.0)) return {false, JuryFailure::condition_i};  // S3 eq. (31) (i)
  const double D11 = 1.0 - d4 * d4;  // S3 eq. (31), corrected (OCR: 1 - d1^2)
  const double D12 = d2 * (1.0 - d4);
  const double D13 = d1 - d3 * d4;
  const double D14 = d3 - d1 * d4;
  if (!(std::fabs(D14) < std::fabs(D11))) return {false, JuryFailure::condition_ii};  // (ii)
  const double D21 = (D11 * D11 - D14 * D14) / D11;
  const double D22 = (D11 * D13 - D12 * D14) / D11;
  const double D23 = (D11 * D12 - D13 * D14) / D11;
  if (!(std::fabs(D23) < std::fabs(D21))) return {false, JuryFailure::condition_iii};  // (iii)
  const double D31 = (D21 * D21 - D23 * D23) / D21;
  const double D32 = D22 * (D21 - D23) / D21;
  if (!(std::fabs(D32) < std::fabs(D31))) return {false, JuryFailure::condition_iv};  // (iv)
  return {true, JuryFailure::none};
}

}  // namespace tnv::fw::arsc
