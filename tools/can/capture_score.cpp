#include "tools/can/capture_score.hpp"

#include <cmath>

namespace tnv::can_host {

namespace {

struct Columns {
  const std::vector<double>* motion_tick = nullptr;
  const std::vector<double>* contour_um = nullptr;
  const std::vector<double>* ref_x = nullptr;
  const std::vector<double>* ref_y = nullptr;
  const std::vector<double>* pos_x = nullptr;
  const std::vector<double>* pos_y = nullptr;
  bool has_path() const { return ref_x && ref_y && pos_x && pos_y; }
};

Columns columns_of(const CaptureTable& t) {
  return {t.column("motion_tick"), t.column("contour"), t.column("ref_x"),
          t.column("ref_y"),       t.column("pos_x"),   t.column("pos_y")};
}

// The sample's contour error, mm.
double contour_mm(const Columns& c, std::size_t i) {
  if (c.contour_um) return (*c.contour_um)[i] / 1000.0;
  // S1 eq. (33) from the captured path (nm resolution).
  return hil::contour_error_mm((*c.ref_x)[i], (*c.ref_y)[i], (*c.pos_x)[i], (*c.pos_y)[i]);
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
      t.reference_mm = {(*c.ref_x)[i], (*c.ref_y)[i]};
      t.position_mm = {(*c.pos_x)[i], (*c.pos_y)[i]};
    }
    if (const auto* v = table.column("command_x")) t.command_mm_s[0] = (*v)[i];
    if (const auto* v = table.column("command_y")) t.command_mm_s[1] = (*v)[i];
    if (const auto* v = table.column("s_x")) t.s[0] = (*v)[i];
    if (const auto* v = table.column("s_y")) t.s[1] = (*v)[i];
    if (const auto* v = table.column("d_hat_x")) t.d_hat_mm_s[0] = (*v)[i];
    if (const auto* v = table.column("d_hat_y")) t.d_hat_mm_s[1] = (*v)[i];
    t.contour_um = contour_mm(c, i) * 1000.0;
    trace.push_back(t);
  }
  return trace;
}

double reference_radius_mm(const CaptureTable& table) {
  const Columns c = columns_of(table);
  if (!c.ref_x || !c.ref_y) return 0.0;
  for (std::size_t i = 0; i < table.samples(); ++i)
    if (!c.motion_tick || (*c.motion_tick)[i] >= 0) return std::hypot((*c.ref_x)[i], (*c.ref_y)[i]);
  return 0.0;
}

}  // namespace tnv::can_host
