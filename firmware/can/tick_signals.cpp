#include "firmware/can/tick_signals.hpp"

#include <cmath>

#include "firmware/io/force_code.hpp"

namespace tnv::fw::can {

double contour_um(const TickTask& task, const TickRecord& r) noexcept {
  if (r.motion_tick < 0 || !task.circle_motion()) return 0.0;
  // The circle lies in the XY plane.
  const double cx = task.circle_centre_mm(hal::kPlaneFirst);
  const double cy = task.circle_centre_mm(hal::kPlaneSecond);
  const AxisTickRecord& x = r.axis[hal::index(hal::kPlaneFirst)];
  const AxisTickRecord& y = r.axis[hal::index(hal::kPlaneSecond)];
  // S1 eq. (33); with the centre at the origin exactly tnv-hil's contour_error_mm().
  const double e_mm = std::fabs(std::hypot(x.reference_mm - cx, y.reference_mm - cy) -
                                std::hypot(x.position_mm - cx, y.position_mm - cy));
  return e_mm * 1000.0;
}

double force_n(const TickRecord& r, const NodeSettings& settings) noexcept {
  return force_code_to_n(r.force_code, settings.firmware.force_sensor.n_per_volt);
}

TickSignals tick_signals(const TickTask& task, const NodeSettings& settings) noexcept {
  const TickRecord& r = task.last_record();
  return {contour_um(task, r), force_n(r, settings)};
}

}  // namespace tnv::fw::can
