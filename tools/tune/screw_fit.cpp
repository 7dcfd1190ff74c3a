#include "tools/tune/screw_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "tools/tune/least_squares.hpp"

namespace tnv::tune {

namespace {

constexpr int kHarmonics = 4;
constexpr int kColumns = 3 + 2 * kHarmonics;  // c, b, k, then sin/cos per harmonic
constexpr std::size_t kMinPointsPerDirection = 8;

void fill_row(Eigen::MatrixXd& a, Eigen::Index i, double p_mm, int d, double period_mm) {
  auto row = a.row(i);
  row(0) = p_mm * 1e-3;         // c in um/m: um of error per m of travel
  row(1) = -0.5 * d;            // b in um
  row(2) = 1.0;                 // k in um
  const double w = 2.0 * std::numbers::pi / period_mm;
  for (int h = 1; h <= kHarmonics; ++h) {
    row(1 + 2 * h) = std::sin(h * w * p_mm);
    row(2 + 2 * h) = std::cos(h * w * p_mm);
  }
}

}  // namespace

std::optional<ScrewFit> fit_screw(const std::vector<GaugePoint>& points, double turn_period_mm, std::string& error) {
  if (!(std::isfinite(turn_period_mm) && turn_period_mm >= 0.1 && turn_period_mm <= 1000.0)) {
    error = "the turn period must be 0.1 .. 1000 mm";
    return std::nullopt;
  }
  const auto forward = static_cast<std::size_t>(
      std::count_if(points.begin(), points.end(), [](const GaugePoint& p) { return p.direction > 0; }));
  const std::size_t reverse = points.size() - forward;
  if (forward < kMinPointsPerDirection || reverse < kMinPointsPerDirection) {
    error = "need at least " + std::to_string(kMinPointsPerDirection) + " points approached from each direction (" +
            std::to_string(forward) + " forward, " + std::to_string(reverse) + " reverse): backlash is their difference";
    return std::nullopt;
  }
  const auto [lo, hi] = std::minmax_element(points.begin(), points.end(), [](const GaugePoint& a, const GaugePoint& b) {
    return a.position_mm < b.position_mm;
  });
  const double span_mm = hi->position_mm - lo->position_mm;
  if (span_mm < turn_period_mm) {
    error = "the points span " + std::to_string(span_mm) + " mm, less than one turn period (" +
            std::to_string(turn_period_mm) + " mm): the per-turn error cannot be told from the lead error";
    return std::nullopt;
  }
  const auto n = static_cast<Eigen::Index>(points.size());
  Eigen::MatrixXd a(n, kColumns);
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const GaugePoint& p = points[static_cast<std::size_t>(i)];
    fill_row(a, i, p.position_mm, p.direction, turn_period_mm);
    y(i) = (p.table_mm - p.position_mm) * 1e3;
  }
  const LeastSquares ls = least_squares(a, y);
  if (ls.rank < kColumns) {
    error = "the points do not determine the model (rank " + std::to_string(ls.rank) + " of " +
            std::to_string(kColumns) + "): spread them over at least a turn, at more than 8 phases of it";
    return std::nullopt;
  }
  const Eigen::VectorXd& x = ls.x;
  ScrewFit fit;
  fit.lead_um_per_m = x(0);
  fit.backlash_um = x(1);
  fit.turn_period_mm = turn_period_mm;
  fit.points = points.size();
  fit.span_mm = span_mm;
  for (std::size_t j = 0; j < fw::kTurnErrorPoints; ++j) {
    const double phase = 2.0 * std::numbers::pi * static_cast<double>(j) / static_cast<double>(fw::kTurnErrorPoints);
    double e_um = 0.0;
    for (int h = 1; h <= kHarmonics; ++h) e_um += x(1 + 2 * h) * std::sin(h * phase) + x(2 + 2 * h) * std::cos(h * phase);
    fit.turn_error_um[j] = e_um;
  }
  const Eigen::VectorXd residual = y - a * x;
  fit.error_rms_um = std::sqrt((y.array() - y.mean()).square().mean());
  fit.residual_rms_um = std::sqrt(residual.array().square().mean());
  fit.residual_max_um = residual.cwiseAbs().maxCoeff();
  return fit;
}

fw::ScrewCompensation to_compensation(const ScrewFit& fit, const fw::ScrewCompensation& base) {
  fw::ScrewCompensation c = base;
  c.backlash_mm = std::max(0.0, fit.backlash_um) * 1e-3;  // a negative lash is noise: no compensation
  c.lead_um_per_m = fit.lead_um_per_m;
  c.turn_period_mm = fit.turn_period_mm;
  for (std::size_t j = 0; j < fw::kTurnErrorPoints; ++j) c.turn_error_mm[j] = fit.turn_error_um[j] * 1e-3;
  return c;
}

double fitted_error_um(const ScrewFit& fit, double position_mm, int direction) {
  fw::ScrewCompensation c = to_compensation(fit, fw::ScrewCompensation{});
  return fit.lead_um_per_m * position_mm * 1e-3 - 0.5 * direction * fit.backlash_um +
         fw::turn_error_mm(c, position_mm) * 1e3;
}

}  // namespace tnv::tune
