#include "tools/serve/telemetry_sample.hpp"

#include <limits>
#include <optional>

namespace tnv::serve {

namespace {

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

}  // namespace

ScopeSample scope_sample(const can_host::TelemetryView& view, double t_s) {
  ScopeSample s;
  s.t_s = t_s;
  // In kScopeChannels' order: kind by kind, each kind axis by axis.
  std::size_t k = 0;
  const auto per_axis = [&](const std::optional<std::array<double, hal::kAxisCount>>& v, double scale) {
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) s.values[k++] = v ? (*v)[i] * scale : kNone;
  };
  per_axis(view.position_mm, 1.0);
  per_axis(view.following_mm, 1e3);  // the frame carries mm; the page shows um
  per_axis(view.s_mm_s, 1.0);
  per_axis(view.d_hat_mm_s, 1.0);
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) s.values[k++] = view.output ? view.output->dac_code[i] : kNone;
  s.values[k++] = view.output ? view.output->force_n : kNone;
  s.values[k++] = view.contour ? view.contour->contour_um : kNone;
  s.values[k++] = view.spindle ? view.spindle->measured_rpm : kNone;
  return s;
}

}  // namespace tnv::serve
