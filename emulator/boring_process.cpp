#include "emulator/boring_process.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "emulator/scenario_validation.hpp"

namespace tnv::emu {

namespace {

constexpr double kTable1Gamma = 0.9777;
constexpr double kTable1DepthMm = 2.5;

BoringParameterSet from_c(int first_part, double c_mm, double alpha, double beta) {
  return {first_part, c_mm / std::pow(kTable1DepthMm, kTable1Gamma), alpha, beta, kTable1Gamma};
}

std::string bad(const char* field, const std::string& why) { return std::string(field) + ": " + why; }

}  // namespace

BoringProcessConfig paper_boring_process(double sigma_d_mm, std::uint64_t seed, int change_at_1, int change_at_2) {
  BoringProcessConfig c;
  c.sigma_d_mm = sigma_d_mm;
  c.seed = seed;
  c.depth_of_cut_mm = kTable1DepthMm;
  c.sets.push_back(from_c(1, 0.0871, 0.5025, 0.2676));  // Table 1
  if (change_at_1 > 1) c.sets.push_back(from_c(change_at_1, 0.15, 0.7, 0.4));  // section 5, second set
  if (change_at_2 > 1 && change_at_2 > change_at_1) c.sets.push_back(from_c(change_at_2, 0.075, 0.6, 0.5));
  return c;
}

BoringProcessConfig unchanged_boring_process(double sigma_d_mm, std::uint64_t seed) {
  return paper_boring_process(sigma_d_mm, seed, 0, 0);
}

std::string validate_boring_process(const BoringProcessConfig& c) {
  if (c.sets.empty()) return bad("sets", "at least one parameter set is needed");
  if (c.sets.front().first_part != 1) return bad("sets[0].first_part", "must be 1 (the first set starts at part 1)");
  for (std::size_t i = 0; i < c.sets.size(); ++i) {
    const BoringParameterSet& s = c.sets[i];
    const std::string at = "sets[" + std::to_string(i) + "].";
    if (i > 0 && s.first_part <= c.sets[i - 1].first_part)
      return at + "first_part: must be greater than the previous set's (got " + std::to_string(s.first_part) + ")";
    if (!(std::isfinite(s.k_mm) && s.k_mm > 0.0)) return at + "k_mm: must be > 0 and finite (got " + format_number(s.k_mm) + ")";
    if (!(std::isfinite(s.alpha) && s.alpha > 0.0 && s.alpha <= 3.0))
      return at + "alpha: must be in (0, 3] (got " + format_number(s.alpha) + ")";
    if (!(std::isfinite(s.beta) && s.beta >= 0.0 && s.beta <= 3.0))
      return at + "beta: must be in [0, 3] (got " + format_number(s.beta) + ")";
    if (!(std::isfinite(s.gamma) && s.gamma >= 0.0 && s.gamma <= 3.0))
      return at + "gamma: must be in [0, 3] (got " + format_number(s.gamma) + ")";
  }
  if (!(std::isfinite(c.depth_of_cut_mm) && c.depth_of_cut_mm > 0.0))
    return bad("depth_of_cut_mm", "must be > 0 and finite (got " + format_number(c.depth_of_cut_mm) + ")");
  if (!(std::isfinite(c.sigma_d_mm) && c.sigma_d_mm >= 0.0))
    return bad("sigma_d_mm", "must be >= 0 and finite (got " + format_number(c.sigma_d_mm) + ")");
  if (!(std::isfinite(c.preset_deflection_mm) && c.preset_deflection_mm >= 0.0))
    return bad("preset_deflection_mm", "must be >= 0 and finite (got " + format_number(c.preset_deflection_mm) + ")");
  if (!(std::isfinite(c.force_angle_deg) && c.force_angle_deg >= 0.0 && c.force_angle_deg < 90.0))
    return bad("force_angle_deg", "must be in [0, 90) (got " + format_number(c.force_angle_deg) + ")");
  if (!(std::isfinite(c.gauge_noise_mm_rms) && c.gauge_noise_mm_rms >= 0.0))
    return bad("gauge_noise_mm_rms", "must be >= 0 and finite (got " + format_number(c.gauge_noise_mm_rms) + ")");
  if (!(std::isfinite(c.gauge_resolution_mm) && c.gauge_resolution_mm >= 0.0))
    return bad("gauge_resolution_mm", "must be >= 0 and finite (got " + format_number(c.gauge_resolution_mm) + ")");
  return {};
}

BoringProcess::BoringProcess(BoringProcessConfig config) : config_(std::move(config)), rng_(config_.seed),
      gauge_noise_(make_noise_stream(config_.gauge_seed, NoiseStreamId::bore_gauge)) {
  if (const std::string error = validate_boring_process(config_); !error.empty()) throw std::invalid_argument(error);
}

const BoringParameterSet& BoringProcess::parameters(int part) const {
  const BoringParameterSet* found = &config_.sets.front();
  for (const BoringParameterSet& s : config_.sets)
    if (part >= s.first_part) found = &s;
  return *found;
}

double BoringProcess::c_mm(int part) const {
  const BoringParameterSet& s = parameters(part);
  return s.k_mm * std::pow(config_.depth_of_cut_mm, s.gamma);  // S4 eq. (2): C = K a^gamma
}

double BoringProcess::deflection_mm(int part, double infeed_mm_rev, double overhang_mm) const {
  const BoringParameterSet& s = parameters(part);
  // S4 eq. (1): d = K S^alpha L^beta a^gamma
  return s.k_mm * std::pow(infeed_mm_rev, s.alpha) * std::pow(overhang_mm, s.beta) *
         std::pow(config_.depth_of_cut_mm, s.gamma);
}

double BoringProcess::optimal_infeed_mm_rev(int part, double overhang_mm) const {
  const BoringParameterSet& s = parameters(part);
  // S4 eq. (3) with the true parameters.
  return std::pow(config_.preset_deflection_mm / (c_mm(part) * std::pow(overhang_mm, s.beta)), 1.0 / s.alpha);
}

double BoringProcess::measure_bore_error_mm(int part, double infeed_mm_rev, double overhang_mm) {
  return sample_bore(part, infeed_mm_rev, overhang_mm).reading_mm;
}

BoreSample BoringProcess::sample_bore(int part, double infeed_mm_rev, double overhang_mm) {
  const double d = deflection_mm(part, infeed_mm_rev, overhang_mm) + config_.sigma_d_mm * gaussian();
  const double cos_phi = std::cos(config_.force_angle_deg * std::numbers::pi / 180.0);
  double delta_mm = 2.0 * cos_phi * (d - config_.preset_deflection_mm);  // S4 eq. (11) solved for delta
  if (config_.gauge_noise_mm_rms > 0.0) delta_mm += config_.gauge_noise_mm_rms * gauge_noise_.normal();
  if (config_.gauge_resolution_mm > 0.0)
    delta_mm = config_.gauge_resolution_mm * std::round(delta_mm / config_.gauge_resolution_mm);
  return BoreSample{.radius_error_mm = d - config_.preset_deflection_mm, .reading_mm = delta_mm};
}

// Marsaglia's polar method on 53-bit uniforms from mt19937_64: the same
// numbers from every standard library (std::normal_distribution is not).
double BoringProcess::gaussian() {
  if (have_spare_) {
    have_spare_ = false;
    return spare_;
  }
  double u = 0.0;
  double v = 0.0;
  double s = 0.0;
  do {
    u = 2.0 * (static_cast<double>(rng_() >> 11) * 0x1.0p-53) - 1.0;
    v = 2.0 * (static_cast<double>(rng_() >> 11) * 0x1.0p-53) - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double f = std::sqrt(-2.0 * std::log(s) / s);
  spare_ = v * f;
  have_spare_ = true;
  return u * f;
}

}  // namespace tnv::emu
