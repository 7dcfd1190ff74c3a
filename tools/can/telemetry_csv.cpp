#include "tools/can/telemetry_csv.hpp"

#include <cstdio>
#include <optional>

#include "firmware/supervisor/fault.hpp"
#include "firmware/tick/tick_record.hpp"
#include "hal/axis.hpp"

namespace tnv::can_host {

namespace {

void cell(std::string& row, std::optional<double> value) {
  row += ',';
  if (!value) return;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", *value);
  row += buf;
}

template <typename T, typename F>
std::optional<double> field(const std::optional<T>& part, F&& get) {
  return part ? std::optional<double>{get(*part)} : std::nullopt;
}

}  // namespace

std::string telemetry_csv_header() {
  std::string out = "t_s,frames,bus_load,state,fault";
  // The per-axis columns, kind by kind, from the axis list.
  for (const char* kind : {"pos_%s_mm", "following_%s_um", "s_%s_mm_s", "d_hat_%s_mm_s", "dac_%s"})
    for (const hal::Axis a : hal::kAxes) {
      char name[32];
      std::snprintf(name, sizeof name, kind, hal::axis_label(a));
      out.append(",").append(name);
    }
  return out +
         ",force_n,contour_um,arsc_force_n,arsc_force_ref_n,feed_override,cutting_gain_n_per_mm_s,spindle_state,"
         "spindle_target_rpm,spindle_command_rpm,spindle_measured_rpm,spindle_at_speed";
}

std::string telemetry_csv_row(const TelemetryView& v, double t_s, double bus_load) {
  char head[96];
  std::snprintf(head, sizeof head, "%.6f,%llu,%.6f,", t_s, static_cast<unsigned long long>(v.frames), bus_load);
  std::string row = head;
  if (v.heartbeat) row.append(fw::to_string(v.heartbeat->state)).append(",").append(fw::to_string(v.heartbeat->fault));
  else row += ',';
  using PerAxis = std::array<double, hal::kAxisCount>;
  constexpr std::size_t kAxes = hal::kAxisCount;
  for (std::size_t axis = 0; axis < kAxes; ++axis) cell(row, field(v.position_mm, [axis](const PerAxis& p) { return p[axis]; }));
  for (std::size_t axis = 0; axis < kAxes; ++axis)
    cell(row, field(v.following_mm, [axis](const PerAxis& p) { return p[axis] * 1e3; }));
  for (std::size_t axis = 0; axis < kAxes; ++axis) cell(row, field(v.s_mm_s, [axis](const PerAxis& p) { return p[axis]; }));
  for (std::size_t axis = 0; axis < kAxes; ++axis)
    cell(row, field(v.d_hat_mm_s, [axis](const PerAxis& p) { return p[axis]; }));
  for (std::size_t axis = 0; axis < kAxes; ++axis)
    cell(row, field(v.output, [axis](const OutputTelemetry& o) { return o.dac_code[axis]; }));
  cell(row, field(v.output, [](const OutputTelemetry& o) { return o.force_n; }));
  cell(row, field(v.contour, [](const ContourTelemetry& c) { return c.contour_um; }));
  cell(row, field(v.arsc, [](const ArscTelemetry& a) { return a.force_n; }));
  cell(row, field(v.arsc, [](const ArscTelemetry& a) { return a.force_ref_n; }));
  cell(row, field(v.arsc, [](const ArscTelemetry& a) { return a.feed_override; }));
  cell(row, field(v.arsc, [](const ArscTelemetry& a) { return a.cutting_gain_n_per_mm_s; }));
  row += ',';
  if (v.spindle) row += spindle_state(*v.spindle);
  cell(row, field(v.spindle, [](const SpindleTelemetry& s) { return s.target_rpm; }));
  cell(row, field(v.spindle, [](const SpindleTelemetry& s) { return s.command_rpm; }));
  cell(row, field(v.spindle, [](const SpindleTelemetry& s) { return s.measured_rpm; }));
  cell(row, field(v.spindle, [](const SpindleTelemetry& s) { return s.at_speed() ? 1.0 : 0.0; }));
  return row;
}

}  // namespace tnv::can_host
