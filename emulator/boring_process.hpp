#pragma once
// The boring process the S4 planner is judged against (Lee 1983, after
// Sun, Wu & Eman 1983): spindle deflection
//   d = K S^alpha L^beta a^gamma            S4 eq. (1)
// (constant depth a: d = C S^alpha L^beta, C = K a^gamma, eq. (2)), with
// parameter sets that take over at given part numbers, and a post-process
// gauge that reads the diametral bore error at an overhang L:
//   delta = 2 cos phi (d + e - d_preset),  e ~ N(0, sigma_d)   (eq. (11))
// The tool is preset so that a deflection of d_preset cuts the nominal
// bore. The noise is drawn from a seeded generator of our own (same
// numbers on every platform). A bench's gauge adds its own error to the
// reading (off by default): Gaussian repeatability on delta, then the
// reading's step, from a stream of its own (noise_stream.hpp), so switching
// it on leaves e's sequence as it was. Knows nothing about any planner.
#include <cstdint>
#include <random>

#include "emulator/noise_stream.hpp"
#include <string>
#include <vector>

namespace tnv::emu {

struct BoringParameterSet {
  int first_part = 1;   // this set applies from this part on
  double k_mm = 0.0;    // K of eq. (1)
  double alpha = 0.0;   // infeed exponent
  double beta = 0.0;    // overhang exponent
  double gamma = 0.0;   // depth-of-cut exponent
};

struct BoringProcessConfig {
  std::vector<BoringParameterSet> sets;  // first_part strictly increasing, the first is part 1
  double depth_of_cut_mm = 2.5;          // a (Table 1)
  double sigma_d_mm = 0.016231;          // gauge noise as deflection, 1 sigma (Table 1)
  double preset_deflection_mm = 0.1165;  // d_preset: deflection that cuts the nominal bore (= d0)
  double force_angle_deg = 60.0;         // phi (Sun et al.)
  std::uint64_t seed = 1;
  // The gauge's own error on the diametral reading delta ([noise] bore_gauge_*; 0 = an exact gauge).
  double gauge_noise_mm_rms = 0.0;
  double gauge_resolution_mm = 0.0;      // the reading is rounded to this step; 0 = continuous
  std::uint64_t gauge_seed = 0;
};

// Table 1 and section 5: parts 1-10 alpha 0.5025, beta 0.2676, C 0.0871 mm;
// from part change_at[0] alpha 0.7, beta 0.4, C 0.15 mm; from part
// change_at[1] alpha 0.6, beta 0.5, C 0.075 mm. gamma 0.9777 and a = 2.5 mm
// throughout (K = C / a^gamma; Table 1: 1/K = 28.111 mm^-1).
// A change_at entry <= 1 or beyond any run leaves that set out.
BoringProcessConfig paper_boring_process(double sigma_d_mm, std::uint64_t seed, int change_at_1 = 11,
                                         int change_at_2 = 21);
// The Table 1 set alone, for ever.
BoringProcessConfig unchanged_boring_process(double sigma_d_mm, std::uint64_t seed);

// "" if valid, else "field: reason".
std::string validate_boring_process(const BoringProcessConfig& config);

// One bore reading: the radius error along the deflection, d + e - d_preset,
// and what the gauge shows for it (eq. (11)'s diametral delta, with the
// gauge's own error).
struct BoreSample {
  double radius_error_mm = 0.0;
  double reading_mm = 0.0;
};

class BoringProcess {
 public:
  // Throws std::invalid_argument with validate_boring_process()'s message.
  explicit BoringProcess(BoringProcessConfig config);

  const BoringParameterSet& parameters(int part) const;
  double c_mm(int part) const;  // C = K a^gamma, eq. (2)
  // True deflection (no noise), eq. (1).
  double deflection_mm(int part, double infeed_mm_rev, double overhang_mm) const;
  // The infeed that gives d = d_preset exactly at L with the true set (eq. (3)).
  double optimal_infeed_mm_rev(int part, double overhang_mm) const;
  // Gauge reading at L of a part cut with infeed S there; draws one noise sample.
  double measure_bore_error_mm(int part, double infeed_mm_rev, double overhang_mm);
  // The same draw, with the radius error it came from.
  BoreSample sample_bore(int part, double infeed_mm_rev, double overhang_mm);

  const BoringProcessConfig& config() const { return config_; }

 private:
  double gaussian();

  BoringProcessConfig config_;
  std::mt19937_64 rng_;
  NoiseStream gauge_noise_;
  bool have_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace tnv::emu
