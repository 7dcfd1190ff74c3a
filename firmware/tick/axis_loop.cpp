#include "firmware/tick/axis_loop.hpp"

#include "firmware/compensation/friction_feedforward.hpp"
#include "firmware/io/dac_code.hpp"
#include "firmware/timing/m_method_speed.hpp"

namespace tnv::fw {

AxisLoop::AxisLoop(const AxisConfig& config, unsigned counter_bits) noexcept
    : pid_(config.model, config.pid),
      dvsc_(ControllerKind::dvsc, config.model, config.sliding),
      rdvsc_(ControllerKind::rdvsc, config.model, config.sliding),
      kind_(config.controller),
      encoder_(counter_bits) {
  observer_.configure(config.model, config.observer);
}

AxisController& AxisLoop::active() noexcept {
  switch (kind_) {
    case ControllerKind::pid: return pid_;
    case ControllerKind::dvsc: return dvsc_;
    case ControllerKind::rdvsc: break;
  }
  return rdvsc_;
}

void AxisLoop::count(std::uint32_t raw, double count_mm, std::uint32_t period_clocks) noexcept {
  const std::int64_t delta = encoder_.update(raw);
  speed_mm_s_ = m_method_speed_mm_s(delta, count_mm, period_clocks);
}

void AxisLoop::measure(double origin_mm, const AxisConfig& config, const AxisLimits& limits, bool advanced,
                       std::uint32_t ticks_missed, bool one_nominal_period, AxisTickRecord& r) noexcept {
  const std::int64_t counts = encoder_.counts();
  r.position_mm = origin_mm + static_cast<double>(counts) * config.count_mm;
  r.speed_mm_s = speed_mm_s_;
  if (config.observer.enabled) {
    // Speed observer (speed_observer.hpp): predicted with the command the
    // DAC applied over the last tick, corrected with this count. Restarted
    // from the measurement while the outputs were off or a tick was lost.
    if (r.enabled && advanced && ticks_missed == 0)
      observer_.update(r.position_mm, dac_code_to_speed_mm_s(r.dac_code, config.dac));
    else
      observer_.reset(r.position_mm, r.speed_mm_s);
  }
  stall_.update(counts, r.command_mm_s, r.enabled, limits.stall);
  // What the DAC applied over the interval this snapshot ends (its code, not the unquantised command).
  const double applied_mm_s = r.enabled ? dac_code_to_speed_mm_s(r.dac_code, config.dac) : 0.0;
  plausibility_ = plausibility_monitor_.update(counts, applied_mm_s, advanced && one_nominal_period, config.model,
                                               config.count_mm, config.dac.full_scale_mm_s, limits.plausibility);
}

bool AxisLoop::control(bool on, const AxisConfig& config, const AxisSample& next, double tick_s,
                       AxisExcitations& excite, std::size_t a, AxisTickRecord& r, AxisCheckInput& check) noexcept {
  double u_mm_s = 0.0;
  AxisController& ctl = active();
  double excitation_mm_s = 0.0;
  bool open_loop_ended = false;
  if (on && excite.open_loop(a)) {
    u_mm_s = excite.next(a, encoder_.counts());
    excitation_mm_s = u_mm_s;
    if (!excite.running(a)) {
      // Holding resumes from where the axis came to rest, bumpless.
      ctl.reset();
      open_loop_ended = true;
    }
  } else if (on) {
    AxisState x{r.position_mm, r.speed_mm_s};
    if (const SpeedObserverParams& obs = config.observer; obs.enabled) {
      x.speed_mm_s = observer_.speed_mm_s();
      if (obs.use_position) x.position_mm = observer_.position_mm();
    }
    // The program is for the table, the encoder reads the motor: the
    // controllers follow the motor-side reference (screw_compensation.hpp).
    const ScrewCompensator::Offsets screw =
        screw_.advance(config.screw, r.reference_mm, next.position_mm, tick_s);
    const AxisReference ref{r.reference_mm + screw.now_mm, r.reference_speed_mm_s, next.position_mm + screw.next_mm,
                            next.speed_mm_s};
    u_mm_s = ctl.update(x, ref);
    u_mm_s += friction_feedforward_mm_s(config.friction, r.reference_speed_mm_s, next.speed_mm_s);
    // Closed-loop excitation at the plant input: u = c + d (excitation.hpp).
    if (excite.running(a)) excitation_mm_s = excite.next(a, encoder_.counts());
    u_mm_s += excitation_mm_s;
  }
  r.excitation_mm_s = excitation_mm_s;
  const ControllerSignals sig = ctl.signals();
  r.command_mm_s = u_mm_s;
  r.s = on ? sig.s : 0.0;
  r.d_hat_mm_s = on ? sig.d_hat_mm_s : 0.0;
  // Field by field: a braced temporary is built on the stack and copied
  // with overlapping loads that stall on its own stores (about 4 % of a
  // whole-process circle, docs/performance.md).
  check.position_mm = r.position_mm;
  check.speed_mm_s = r.speed_mm_s;
  check.reference_mm = r.reference_mm;
  check.reference_speed_mm_s = r.reference_speed_mm_s;
  check.command_mm_s = u_mm_s;
  check.stalled_ticks = stall_.stalled_ticks();
  check.stall_command_mm_s = stall_.applied_command_mm_s();
  check.plausibility = plausibility_;
  return open_loop_ended;
}

std::uint16_t AxisLoop::output(bool outputs_live, const DacScale& dac, AxisTickRecord& r) noexcept {
  r.dac_code = outputs_live ? speed_to_dac_code(r.command_mm_s, dac) : dac.mid_code();
  r.enabled = outputs_live;
  return r.dac_code;
}

void AxisLoop::apply(const AxisConfig& from, const AxisConfig& to, bool servo_on, double position_mm) noexcept {
  if (to.model != from.model) {
    pid_ = PidController(to.model, to.pid);
    dvsc_ = RdvscController(ControllerKind::dvsc, to.model, to.sliding);
    rdvsc_ = RdvscController(ControllerKind::rdvsc, to.model, to.sliding);
  } else {
    // Bumpless: each controller keeps its state and re-forms it for the new gains.
    if (to.pid != from.pid) pid_.set_params(to.pid);
    if (to.sliding != from.sliding) {
      dvsc_.set_params(to.sliding);
      rdvsc_.set_params(to.sliding);
    }
  }
  if (to.model != from.model || to.observer != from.observer) {
    observer_.configure(to.model, to.observer);
    observer_.reset(position_mm, speed_mm_s_);
  }
  // The residual's history was formed with the old model and scale.
  if (to.model != from.model || to.count_mm != from.count_mm || to.dac.full_scale_mm_s != from.dac.full_scale_mm_s)
    plausibility_monitor_.reset();
  if (to.controller != kind_) {
    kind_ = to.controller;
    if (servo_on) active().reset();
  }
}

void AxisLoop::reset_controllers() noexcept {
  pid_.reset();
  dvsc_.reset();
  rdvsc_.reset();
}

}  // namespace tnv::fw
