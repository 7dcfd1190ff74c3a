#include "firmware/control/pid_params.hpp"

#include <cmath>

namespace tnv::fw {

ParamCheck validate(const PidParams& p, const AxisModel& model) noexcept {
  struct Field {
    const char* name;
    const double* value;
  };
  const Field fields[] = {{"kp", &p.kp},
                          {"ki", &p.ki},
                          {"kd", &p.kd},
                          {"derivative_filter_tf_s", &p.derivative_filter_tf_s},
                          {"u_max_mm_s", &p.u_max_mm_s}};
  for (const Field& f : fields)
    if (!std::isfinite(*f.value)) return param_error(f.value, f.name, "must be finite (NaN or inf given)");
  if (!(p.kp > 0.0)) return param_error(&p.kp, "kp", "must be > 0");
  if (!(p.ki >= 0.0)) return param_error(&p.ki, "ki", "must be >= 0");
  if (!(p.kd >= 0.0)) return param_error(&p.kd, "kd", "must be >= 0");
  if (!(p.derivative_filter_tf_s >= 0.0))
    return param_error(&p.derivative_filter_tf_s, "derivative_filter_tf_s", "must be >= 0 (0 = off)");
  if (!(p.u_max_mm_s > 0.0)) return param_error(&p.u_max_mm_s, "u_max_mm_s", "must be > 0");
  if (!is_finite(model)) return param_error(&model.B(1), "model", "A, B and period must be finite, period > 0");
  if (p.feedforward && !(std::fabs(model.B(1)) > 1e-12))
    return param_error(&p.feedforward, "feedforward", "needs B2 != 0 in the model (u_ff divides by B2)");
  return param_ok();
}

}  // namespace tnv::fw
