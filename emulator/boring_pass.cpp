#include "emulator/boring_pass.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tnv::emu {

BoringProcessConfig boring_process_config(const Scenario& s) {
  BoringProcessConfig c = paper_boring_process(s.boring.sigma_d_um / 1000.0, s.noise.seed, s.boring.change_at_1,
                                               s.boring.change_at_2);
  c.gauge_noise_mm_rms = s.noise.bore_gauge_um_rms / 1000.0;
  c.gauge_resolution_mm = s.noise.bore_gauge_resolution_um / 1000.0;
  c.gauge_seed = s.noise.seed;
  return c;
}

BoringPass::BoringPass(const BoringAxesParams& params, const StockParams& stock, const BoringProcessConfig& process)
    : params_(params), top_mm_(stock.top_mm), process_(process) {
  begin_part(1);
}

void BoringPass::begin_part(int part) noexcept {
  part_ = part;
  highest_z_mm_ = -std::numeric_limits<double>::infinity();
  cutting_ = false;
  last_deflection_mm_ = 0.0;
  max_radius_error_mm_ = -std::numeric_limits<double>::infinity();
  min_radius_error_mm_ = std::numeric_limits<double>::infinity();
  passes_ = {};
  passes_[0].depth_mm = params_.gauge_top_depth_mm;
  passes_[1].depth_mm = params_.gauge_bottom_depth_mm;
}

double BoringPass::infeed_mm_rev(double vz_mm_s, double spindle_rpm) noexcept {
  const double rev_per_s = std::abs(spindle_rpm) / 60.0;
  if (!(vz_mm_s < 0.0) || !(rev_per_s > 0.0)) return 0.0;
  return -vz_mm_s / rev_per_s;
}

double BoringPass::radius_error_mm(double infeed_mm_rev, double overhang_mm) const {
  return process_.deflection_mm(part_, infeed_mm_rev, overhang_mm) - process_.config().preset_deflection_mm;
}

void BoringPass::advance(double z_tool_mm, double vz_mm_s, double spindle_rpm) noexcept {
  const double infeed = infeed_mm_rev(vz_mm_s, spindle_rpm);
  // In the bore (at or below the stock top) and feeding down with the spindle turning.
  cutting_ = z_tool_mm <= top_mm_ && infeed > 0.0;
  const double overhang = overhang_mm(z_tool_mm);
  if (cutting_) {
    last_deflection_mm_ = process_.deflection_mm(part_, infeed, overhang);
    const double error_mm = last_deflection_mm_ - process_.config().preset_deflection_mm;
    max_radius_error_mm_ = std::max(max_radius_error_mm_, error_mm);
    min_radius_error_mm_ = std::min(min_radius_error_mm_, error_mm);
  }
  // The first cutting sub-step at or below a gauge depth, on a pass that came
  // from at or above it, sets the bore there.
  highest_z_mm_ = std::max(highest_z_mm_, z_tool_mm);
  for (GaugeDepthReading& g : passes_) {
    const double z_gauge_mm = top_mm_ - g.depth_mm;
    if (!g.cut && cutting_ && z_tool_mm <= z_gauge_mm && highest_z_mm_ >= z_gauge_mm) {
      g.cut = true;
      g.overhang_mm = overhang;
      g.infeed_mm_rev = infeed;
    }
  }
}

std::array<GaugeDepthReading, BoringPass::kGaugeDepths> BoringPass::read_gauge() {
  std::array<GaugeDepthReading, kGaugeDepths> out = passes_;
  for (GaugeDepthReading& g : out) {
    if (!g.cut) continue;
    const BoreSample sample = process_.sample_bore(part_, g.infeed_mm_rev, g.overhang_mm);
    g.radius_error_mm = sample.radius_error_mm;
    g.reading_mm = sample.reading_mm;
  }
  return out;
}

}  // namespace tnv::emu
