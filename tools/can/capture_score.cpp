#include "tools/can/capture_score.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <string>

#include "hal/axis.hpp"

namespace tnv::can_host {

namespace {

// The circle is in the XY plane: its columns are the plane axes' (ref_x,
// ref_y, pos_x, pos_y with today's list), in TraceSample's plane order.
constexpr std::array<hal::Axis, 2> kPlane{hal::kPlaneFirst, hal::kPlaneSecond};

std::string column_name(const char* channel, hal::Axis axis) { return std::string(channel) + "_" + hal::axis_label(axis); }

struct Columns {
  const std::vector<double>* motion_tick = nullptr;
  const std::vector<double>* contour_um = nullptr;
  std::array<const std::vector<double>*, 2> ref{};  // per plane axis
  std::array<const std::vector<double>*, 2> pos{};
  bool has_path() const { return ref[0] && ref[1] && pos[0] && pos[1]; }
};

Columns columns_of(const CaptureTable& t) {
  Columns c{t.column("motion_tick"), t.column("contour"), {}, {}};
  for (std::size_t k = 0; k < kPlane.size(); ++k) {
    c.ref[k] = t.column(column_name("ref", kPlane[k]));
    c.pos[k] = t.column(column_name("pos", kPlane[k]));
  }
  return c;
}

// The sample's contour error, mm.
double contour_mm(const Columns& c, std::size_t i) {
  if (c.contour_um) return (*c.contour_um)[i] / 1000.0;
  // S1 eq. (33) from the captured path (nm resolution).
  return hil::contour_error_mm((*c.ref[0])[i], (*c.ref[1])[i], (*c.pos[0])[i], (*c.pos[1])[i]);
}

}  // namespace

std::optional<hil::ContourStats> score_circle(const CaptureTable& table, std::string& error) {
  const Columns c = columns_of(table);
  if (!c.motion_tick || (!c.contour_um && !c.has_path())) {
    error = "the capture cannot score a circle: it needs motion_tick and contour (or ref_x, ref_y, pos_x, pos_y)";
    return std::nullopt;
  }
  hil::ContourAccumulator contour;
  for (std::size_t i = 0; i < table.samples(); ++i)
    if ((*c.motion_tick)[i] >= 0) contour.add(contour_mm(c, i));
  const hil::ContourStats stats = contour.stats();
  if (stats.samples == 0) {
    error = "the capture has no sample in motion (motion_tick >= 0)";
    return std::nullopt;
  }
  return stats;
}

std::vector<hil::TraceSample> circle_trace(const CaptureTable& table) {
  const Columns c = columns_of(table);
  std::vector<hil::TraceSample> trace;
  if (!c.motion_tick || (!c.contour_um && !c.has_path())) return trace;
  for (std::size_t i = 0; i < table.samples(); ++i) {
    const double tick = (*c.motion_tick)[i];
    if (tick < 0) continue;
    hil::TraceSample t;
    t.t_s = tick * 1e-3;
    if (c.has_path()) {
      t.reference_mm = {(*c.ref[0])[i], (*c.ref[1])[i]};
      t.position_mm = {(*c.pos[0])[i], (*c.pos[1])[i]};
    }
    for (std::size_t k = 0; k < kPlane.size(); ++k) {
      if (const auto* v = table.column(column_name("command", kPlane[k]))) t.command_mm_s[k] = (*v)[i];
      if (const auto* v = table.column(column_name("s", kPlane[k]))) t.s[k] = (*v)[i];
      if (const auto* v = table.column(column_name("d_hat", kPlane[k]))) t.d_hat_mm_s[k] = (*v)[i];
    }
    t.contour_um = contour_mm(c, i) * 1000.0;
    trace.push_back(t);
  }
  return trace;
}

double reference_radius_mm(const CaptureTable& table) {
  const Columns c = columns_of(table);
  if (!c.ref[0] || !c.ref[1]) return 0.0;
  for (std::size_t i = 0; i < table.samples(); ++i)
    if (!c.motion_tick || (*c.motion_tick)[i] >= 0) return std::hypot((*c.ref[0])[i], (*c.ref[1])[i]);
  return 0.0;
}

}  // namespace tnv::can_host
