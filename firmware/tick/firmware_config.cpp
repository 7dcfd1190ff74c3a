#include "firmware/tick/firmware_config.hpp"

#include <cmath>
#include <iterator>

#include "firmware/control/pid_tuning.hpp"
#include "firmware/control/same_bytes.hpp"

namespace tnv::fw {

namespace {

// The machine's soft travel limits around home (supervisor and planner).
// X and Y: +-250 mm, a placeholder for the table's travel. Z: the head's
// travel below its home at the top (reference plant "Z axis": 0 to
// -300 mm), with 2 mm above home for the rest error at the switch, still
// 3 mm short of the hard stop 5 mm above the travel: a program whose Z
// (tool length and work offset included) rises beyond it is refused
// `outside_workspace` instead of driving the head into the stop.
void set_machine_travel(hal::Axis axis, AxisLimits& limits) noexcept {
  switch (axis) {
    case hal::Axis::x:
    case hal::Axis::y:
      break;
    case hal::Axis::z:
      limits.position_min_mm = -300.0;
      limits.position_max_mm = 2.0;
      break;
  }
}

}  // namespace

FirmwareConfig default_firmware_config() noexcept {
  FirmwareConfig config;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const hal::Axis axis = hal::axis_from_index(i);
    AxisConfig& a = config.axis[i];
    a.model = paper_axis_model(axis);
    a.sliding = paper_rdvsc_params(axis);
    a.pid = paper_pid_params(axis, a.sliding.u_max_mm_s);
    a.homing = machine_homing_params(axis);
    set_machine_travel(axis, config.supervisor.axis[i]);
  }
  return config;
}

motion::MotionLimits path_limits(const FirmwareConfig& config) noexcept {
  motion::MotionLimits m;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const PathLimits& p = config.axis[i].path;
    m.axis[i] = {p.speed_mm_s, p.accel_mm_s2, p.jerk_mm_s3, config.supervisor.axis[i].position_min_mm,
                 config.supervisor.axis[i].position_max_mm};
  }
  m.tick_period_s = 1e-3;
  m.path_tolerance_mm = config.path_tolerance_mm;
  return m;
}

const void* path_limits_source(const FirmwareConfig& config, const motion::MotionLimits& limits,
                               const void* member) noexcept {
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const motion::AxisLimits& m = limits.axis[i];
    if (member == &m.speed_mm_s) return &config.axis[i].path.speed_mm_s;
    if (member == &m.accel_mm_s2) return &config.axis[i].path.accel_mm_s2;
    if (member == &m.jerk_mm_s3) return &config.axis[i].path.jerk_mm_s3;
    if (member == &m.position_min_mm) return &config.supervisor.axis[i].position_min_mm;
    if (member == &m.position_max_mm) return &config.supervisor.axis[i].position_max_mm;
  }
  if (member == &limits.path_tolerance_mm) return &config.path_tolerance_mm;
  return nullptr;
}

namespace {

// Each axis' section names, generated from the list (static strings: a
// ConfigError points at them).
struct AxisSections {
  const char* axis;
  const char* sliding;
  const char* dvsc;
  const char* pid;
  const char* jog;
  const char* friction;
  const char* observer;
  const char* homing;
  const char* screw;
};
constexpr AxisSections kAxisSections[] = {
#define TNV_AXIS_SECTIONS(name, ...)                                                                          \
  {"axis " #name, "axis " #name ": sliding-mode", "axis " #name ": sliding-mode (gamma = 0)", "axis " #name ": pid", \
   "axis " #name ": jog", "axis " #name ": friction feed-forward", "axis " #name ": speed observer",               \
   "axis " #name ": homing", "axis " #name ": screw compensation"},
    TNV_AXES(TNV_AXIS_SECTIONS)
#undef TNV_AXIS_SECTIONS
};
static_assert(std::size(kAxisSections) == hal::kAxisCount);

ConfigError axis_error(const char* section, const ParamCheck& check) noexcept {
  return {section, check.field, check.reason, check.member};
}

// The member `member` of `copy` is, in `original` (what a check of a copy names).
template <typename T>
const void* in_original(const T& copy, const T& original, const void* member) noexcept {
  const auto* first = reinterpret_cast<const unsigned char*>(&copy);
  const auto* at = static_cast<const unsigned char*>(member);
  if (at < first || at >= first + sizeof(T)) return member;
  return reinterpret_cast<const unsigned char*>(&original) + (at - first);
}

ConfigError validate_parts(const FirmwareConfig& config, const FirmwareConfig* base) noexcept {
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const AxisConfig& a = config.axis[i];
    if (base != nullptr && same_bytes(a, base->axis[i])) continue;
    const AxisSections& names = kAxisSections[i];
    const char* section = names.axis;
    if (!std::isfinite(a.count_mm) || a.count_mm <= 0.0)
      return {section, "count_mm", "must be > 0 and finite", &a.count_mm};
    if (a.dac.bits < 8 || a.dac.bits > 16) return {section, "dac.bits", "must be 8..16", &a.dac.bits};
    if (!std::isfinite(a.dac.full_scale_mm_s) || a.dac.full_scale_mm_s <= 0.0)
      return {section, "dac.full_scale_mm_s", "must be > 0 and finite", &a.dac.full_scale_mm_s};
    if (!std::isfinite(a.home_position_mm)) return {section, "home_position_mm", "must be finite", &a.home_position_mm};
    if (!is_finite(a.model)) return {section, "model", "A and B must be finite with period > 0", &a.model.B(1)};
    if (const ParamCheck c = validate(a.sliding, a.model); !c.ok)
      return axis_error(names.sliding, c);
    SlidingModeParams dvsc = a.sliding;
    dvsc.gamma = 0.0;
    if (ParamCheck c = validate(dvsc, a.model); !c.ok) {
      c.member = in_original(dvsc, a.sliding, c.member);
      return axis_error(names.dvsc, c);
    }
    if (const ParamCheck c = validate(a.pid, a.model); !c.ok) return axis_error(names.pid, c);
    if (a.controller != ControllerKind::pid && a.controller != ControllerKind::dvsc &&
        a.controller != ControllerKind::rdvsc)
      return {section, "controller", "must be pid, dvsc or rdvsc", &a.controller};
    if (const ParamCheck c = validate(a.jog); !c.ok) return axis_error(names.jog, c);
    if (const ParamCheck c = validate(a.friction); !c.ok)
      return axis_error(names.friction, c);
    if (const ParamCheck c = validate(a.observer, a.model); !c.ok)
      return axis_error(names.observer, c);
    if (const ParamCheck c = validate(a.homing); !c.ok) return axis_error(names.homing, c);
    if (const ParamCheck c = validate(a.screw); !c.ok)
      return axis_error(names.screw, c);
  }
  if (base == nullptr || !same_bytes(config.supervisor, base->supervisor))
    if (const ParamCheck c = check(config.supervisor); !c.ok) return {"supervisor", "", c.reason, c.member};
  if (!std::isfinite(config.force_sensor.n_per_volt))
    return {"force sensor", "n_per_volt", "must be finite", &config.force_sensor.n_per_volt};
  // The force loop's check solves its pole placement (a 4x4 system): only when it changed.
  if (base == nullptr || !same_bytes(config.arsc, base->arsc))
    if (const ParamCheck c = arsc::validate(config.arsc); !c.ok) return {"arsc", c.field, c.reason, c.member};
  if (const ParamCheck c = validate(config.spindle); !c.ok) return {"spindle", c.field, c.reason, c.member};
  const motion::MotionLimits limits = path_limits(config);
  if (const ParamCheck c = motion::check(limits); !c.ok)
    return {"path", "", c.reason, path_limits_source(config, limits, c.member)};
  return {};
}

}  // namespace

ConfigError validate(const FirmwareConfig& config) noexcept { return validate_parts(config, nullptr); }

ConfigError validate(const FirmwareConfig& config, const FirmwareConfig& valid_base) noexcept {
  return validate_parts(config, &valid_base);
}

}  // namespace tnv::fw
