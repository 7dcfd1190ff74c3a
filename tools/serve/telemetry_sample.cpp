#include "tools/serve/telemetry_sample.hpp"

#include <limits>
#include <optional>

namespace tnv::serve {

namespace {

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

double axis(const std::optional<std::array<double, 2>>& v, std::size_t i, double scale = 1.0) {
  return v ? (*v)[i] * scale : kNone;
}

}  // namespace

ScopeSample scope_sample(const can_host::TelemetryView& view, double t_s) {
  ScopeSample s;
  s.t_s = t_s;
  s.values = {axis(view.position_mm, 0),
              axis(view.position_mm, 1),
              axis(view.following_mm, 0, 1e3),  // the frame carries mm; the page shows um
              axis(view.following_mm, 1, 1e3),
              axis(view.s_mm_s, 0),
              axis(view.s_mm_s, 1),
              axis(view.d_hat_mm_s, 0),
              axis(view.d_hat_mm_s, 1),
              view.output ? view.output->dac_code[0] : kNone,
              view.output ? view.output->dac_code[1] : kNone,
              view.output ? view.output->force_n : kNone,
              view.contour ? view.contour->contour_um : kNone};
  return s;
}

}  // namespace tnv::serve
