#pragma once
// S4 on real axes (reference plant "Boring (S4, on real axes)"): a boring
// bar on the spindle feeds down in -Z into a pre-drilled hole in the stock.
// Sub-step by sub-step from the tool point's Z, its speed and the
// spindle's actual speed:
//   overhang  L = L0 + (z_top - z_tool)
//   infeed    S = -v_z / (|n| / 60)                mm/rev, while feeding down
//   deflection d = C S^alpha L^beta                 S4 eq. (2), boring_process.hpp
//   radius error there  d - d0 (+ the process noise when the gauge reads it)
// The S and L with which the bar passed each gauge depth are kept; after
// the part the gauge reads the bore there (BoringProcess: the noise e of
// sigma_d on the deflection, eq. (11)'s diametral reading, the gauge's own
// noise and resolution). No infeed (a dwell, or a stopped spindle) is no
// deflection.
#include <array>
#include <cstddef>

#include "emulator/boring_process.hpp"
#include "emulator/scenario.hpp"

namespace tnv::emu {

// The BoringProcess a scenario describes: S4's sets with its change parts,
// sigma_d, and the gauge of [noise] (bore_gauge_um_rms, _resolution_um, seed).
BoringProcessConfig boring_process_config(const Scenario& scenario);

struct GaugeDepthReading {
  bool cut = false;                // the bar passed this depth feeding down
  double depth_mm = 0.0;           // below the stock top
  double overhang_mm = 0.0;        // L as it passed
  double infeed_mm_rev = 0.0;      // S as it passed
  double radius_error_mm = 0.0;    // d - d0 + e
  double reading_mm = 0.0;         // the gauge's diametral reading
};

class BoringPass {
 public:
  static constexpr std::size_t kGaugeDepths = 2;  // top, bottom

  BoringPass(const BoringAxesParams& params, const StockParams& stock, const BoringProcessConfig& process);

  // A new part (from 1): forgets the last part's passes.
  void begin_part(int part) noexcept;
  // One sub-step: tool point z and its speed, the spindle's actual speed.
  void advance(double z_tool_mm, double vz_mm_s, double spindle_rpm) noexcept;
  // After the part: the gauge at both depths (draws the noise once per depth cut).
  std::array<GaugeDepthReading, kGaugeDepths> read_gauge();

  double overhang_mm(double z_tool_mm) const noexcept { return params_.overhang_at_top_mm + (top_mm_ - z_tool_mm); }
  static double infeed_mm_rev(double vz_mm_s, double spindle_rpm) noexcept;
  // Noise-free radius error at this infeed and overhang for the current part.
  double radius_error_mm(double infeed_mm_rev, double overhang_mm) const;

  // Along the current pass, while cutting: the last values and the extremes of d - d0.
  bool cutting() const noexcept { return cutting_; }
  double last_deflection_mm() const noexcept { return last_deflection_mm_; }
  double max_radius_error_mm() const noexcept { return max_radius_error_mm_; }
  double min_radius_error_mm() const noexcept { return min_radius_error_mm_; }
  int part() const noexcept { return part_; }
  BoringProcess& process() noexcept { return process_; }

 private:
  BoringAxesParams params_;
  double top_mm_;
  BoringProcess process_;
  int part_ = 1;
  double highest_z_mm_ = 0.0;  // of this part's pass so far
  bool cutting_ = false;
  double last_deflection_mm_ = 0.0;
  double max_radius_error_mm_ = 0.0;
  double min_radius_error_mm_ = 0.0;
  std::array<GaugeDepthReading, kGaugeDepths> passes_{};
};

}  // namespace tnv::emu
