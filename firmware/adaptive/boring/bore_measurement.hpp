#pragma once
// A post-process measurement of one bored part at one position, and the
// deflection it implies (S4 eq. (11)):
//   d = d0 + delta / (2 cos phi)
// delta is the diametral bore error (nominal minus measured diameter,
// positive = undersize): the tool is preset so that a deflection of d0
// cuts the nominal bore, and the deflection acts at phi to the radius
// (Sun et al.: phi ~ 60 deg).
#include <cmath>

namespace tnv::fw {

struct BoreMeasurement {
  double overhang_mm = 0.0;    // L where the bore was measured
  double infeed_mm_rev = 0.0;  // S the part was cut with at that L
  double bore_error_mm = 0.0;  // delta: diametral undersize
};

// S4 eq. (11).
inline double deflection_from_bore_error_mm(double bore_error_mm, double target_deflection_mm,
                                            double force_angle_deg) noexcept {
  const double phi_rad = force_angle_deg * 3.14159265358979323846 / 180.0;
  return target_deflection_mm + bore_error_mm / (2.0 * std::cos(phi_rad));
}

// Inverse of eq. (11): the bore error a deflection produces.
inline double bore_error_from_deflection_mm(double deflection_mm, double target_deflection_mm,
                                            double force_angle_deg) noexcept {
  const double phi_rad = force_angle_deg * 3.14159265358979323846 / 180.0;
  return 2.0 * std::cos(phi_rad) * (deflection_mm - target_deflection_mm);
}

}  // namespace tnv::fw
