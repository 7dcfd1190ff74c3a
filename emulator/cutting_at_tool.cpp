#include "emulator/cutting_at_tool.hpp"

#include <algorithm>
#include <cmath>

namespace tnv::emu {

namespace {

constexpr double kLookPeriodS = 1e-3;         // the tool looks at the height field at least once a tick,
constexpr double kEngagedLookMoveMm = 0.05;  // and after half a cell of XY travel (a rapid out of the cut);
constexpr double kLookMoveMm = 1e-3;         // one not engaged over the stock after 1 um
constexpr double kMovingMmPerS = 0.05;       // the XY speed under which the tool is at rest (the feed judge's)

}  // namespace

CuttingAtTool::CuttingAtTool(const Scenario& s, double substep_s)
    : tool_(s.tool),
      stock_(s.stock),
      surface_(s.stock),
      probe_(s.probe, stock_),
      probe_tip_mm_(s.probe.tip_radius_mm),
      force_(s.tool_cut, s.tool, substep_s),
      crashes_(s.tool_cut.crash_speed_fraction),
      substeps_per_look_(std::max(1, static_cast<int>(std::lround(kLookPeriodS / substep_s)))) {}

// a_p = the highest material under the tool less the tool point's z, from
// the last look (before that look took the material away). A tool feeding
// into uncut stock meets the top at its leading edge at every look, so a_p
// is the reference plant's z_top - z exactly; one over its own cut meets
// the floor it left. Looks: once a tick while engaged (or after half a
// cell's travel); while not, once the tool has moved 1 um in XY over the
// stock, or beside it as far as its disc is from the stock's side (so the
// sub-step it reaches the side is the one the block engages it at);
// going straight down, the same cells: the last look's height holds. None
// above the stock top.
void CuttingAtTool::advance(const ToolPointMotion& at, double spindle_rpm, double commanded_rpm,
                            double time_s) noexcept {
  if (!(at.z_mm < surface_.top_mm())) {
    material_top_mm_ = -std::numeric_limits<double>::infinity();
    looked_ = false;
    met_count_ = 0;  // what it met before it rose is not under it when it comes down elsewhere
  } else {
    const bool engaged_now = material_top_mm_ > at.z_mm;
    const double moved_xy_mm = std::hypot(at.x_mm - looked_x_mm_, at.y_mm - looked_y_mm_);
    ++substeps_since_look_;
    if (!looked_ || substeps_since_look_ >= substeps_per_look_ || moved_xy_mm > kEngagedLookMoveMm ||
        (!engaged_now && moved_xy_mm > clearance_mm_)) {
      look(at);
    }
  }
  depth_mm_ = std::clamp(material_top_mm_ - at.z_mm, 0.0, tool_.flute_length_mm);
  crashes_.observe(engaged(), CrashEvent{.time_s = time_s,
                                         .x_mm = at.x_mm,
                                         .y_mm = at.y_mm,
                                         .z_mm = at.z_mm,
                                         .spindle_rpm = spindle_rpm,
                                         .commanded_rpm = commanded_rpm});
  force_.advance(at.vx_mm_s, at.vy_mm_s, depth_mm_, spindle_rpm);
}

// The tool takes the material under it down to its point. A tool moving
// through material meets new cells only as they enter its disc (a cell,
// 0.1 mm, at a time), so one look may meet none: while the tool moves, a_p
// is from the highest material met over its last cell of XY travel (the
// looks in that window, at most kMetWindow of them), so a slow feed does
// not read a_p = 0 between two cells; at rest, from this look alone (0 in
// its own cut).
void CuttingAtTool::look(const ToolPointMotion& at) {
  const double met_mm = surface_.cut(at.x_mm, at.y_mm, 0.5 * tool_.diameter_mm, at.z_mm);
  const bool moving = std::hypot(at.vx_mm_s, at.vy_mm_s) >= kMovingMmPerS;
  if (!moving) {
    met_count_ = 0;
    material_top_mm_ = met_mm;
  } else {
    travel_mm_ += looked_ ? std::hypot(at.x_mm - looked_x_mm_, at.y_mm - looked_y_mm_) : 0.0;
    met_[met_next_] = Met{.travel_mm = travel_mm_, .top_mm = met_mm};
    met_next_ = (met_next_ + 1) % kMetWindow;
    met_count_ = std::min(met_count_ + 1, kMetWindow);
    material_top_mm_ = met_mm;
    for (std::size_t k = 1; k < met_count_; ++k) {
      const Met& m = met_[(met_next_ + kMetWindow - 1 - k) % kMetWindow];
      if (!(travel_mm_ - m.travel_mm < StockSurface::kCellMm)) {
        met_count_ = k;  // older looks are out of the window
        break;
      }
      material_top_mm_ = std::max(material_top_mm_, m.top_mm);
    }
  }
  // Beside the stock (no cell under the disc) it meets nothing until it has moved as far as the side.
  const double beside_mm = stock_.xy_distance_mm(at.x_mm, at.y_mm) - 0.5 * tool_.diameter_mm;
  clearance_mm_ = std::isinf(met_mm) ? std::max(beside_mm, 0.0) : kLookMoveMm;
  looked_x_mm_ = at.x_mm;
  looked_y_mm_ = at.y_mm;
  looked_ = true;
  substeps_since_look_ = 0;
}

bool CuttingAtTool::probe_touches(double x_mm, double y_mm, double z_mm) const noexcept {
  if (!probe_.triggered(x_mm, y_mm, z_mm)) return false;  // clear of the block as it came
  if (stock_.xy_distance_mm(x_mm, y_mm) > 0.0) return true;  // its side (the sides are never cut)
  return std::max(z_mm - surface_.height_mm(x_mm, y_mm), 0.0) <= probe_tip_mm_;
}

}  // namespace tnv::emu
