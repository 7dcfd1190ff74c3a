#pragma once
// Contour-error statistics of the S1 circle experiment.
#include <cmath>
#include <cstddef>
#include <span>

namespace tnv::hil {

// S1 eq. (33): e_c = | sqrt(x_ref^2 + y_ref^2) - sqrt(x^2 + y^2) |, circle centred at the origin.
inline double radius_mm(double x_mm, double y_mm) noexcept { return std::hypot(x_mm, y_mm); }
inline double contour_error_mm(double reference_radius_mm, double measured_radius_mm) noexcept {
  return std::fabs(reference_radius_mm - measured_radius_mm);
}
inline double contour_error_mm(double x_ref_mm, double y_ref_mm, double x_mm, double y_mm) noexcept {
  return contour_error_mm(radius_mm(x_ref_mm, y_ref_mm), radius_mm(x_mm, y_mm));
}

struct ContourStats {
  double max_um = 0.0;
  double mean_um = 0.0;
  double std_um = 0.0;  // population standard deviation
  std::size_t samples = 0;
};

// Streaming max / mean / population std (Welford).
class ContourAccumulator {
 public:
  void add(double error_mm) noexcept;
  ContourStats stats() const noexcept;

 private:
  std::size_t n_ = 0;
  double max_um_ = 0.0;
  double mean_um_ = 0.0;
  double m2_um2_ = 0.0;
};

// Seed average: the mean of each statistic over runs.
ContourStats average(std::span<const ContourStats> runs) noexcept;

}  // namespace tnv::hil
