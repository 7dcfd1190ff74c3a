#include "tools/hil/screw_map_run.hpp"

#include <cmath>
#include <memory>

#include "emulator/noise_stream.hpp"
#include "tools/hil/command_status_text.hpp"
#include "tools/hil/hil_rig.hpp"

namespace tnv::hil {

namespace {

constexpr double kRampS = 0.02;
constexpr double kMoveTimeoutS = 60.0;

class MapSession {
 public:
  MapSession(HilRig& rig, const ScrewMapOptions& o) : rig_(rig), o_(o), a_(hal::index(o.axis)), noise_(o.seed, 0) {}

  double position_mm() const { return rig_.task.last_record().axis[a_].position_mm; }

  // Moves the axis by distance_mm (a point-to-point move), then waits settle_s.
  bool move_by(double distance_mm, std::string& error) {
    if (std::fabs(distance_mm) < 1e-9) return settle(error);
    fw::MoveSpec spec;
    spec.axis = o_.axis;
    spec.distance_mm = distance_mm;
    spec.ramp_s = kRampS;
    spec.speed_mm_s = std::min(o_.speed_mm_s, std::fabs(distance_mm) / kRampS);
    if (const fw::CommandStatus st = rig_.task.start_move(spec); st != fw::CommandStatus::ok) {
      error = "move by " + std::to_string(distance_mm) + " mm refused: " + command_status_text(st, rig_.task);
      return false;
    }
    const double start_s = rig_.machine.time_s();
    while (rig_.task.moving() && rig_.machine.time_s() - start_s < kMoveTimeoutS) rig_.tick();
    return settle(error);
  }

  // Moves to target_mm (encoder frame) and records a point approached from `direction`.
  bool record_at(double target_mm, int direction, std::vector<GaugePoint>& out, std::string& error) {
    if (!move_by(target_mm - position_mm(), error)) return false;
    const double table_mm = rig_.machine.truth(o_.axis).position_mm + o_.reference_noise_um_rms * 1e-3 * noise_.normal();
    out.push_back({position_mm(), direction, table_mm});
    return true;
  }

 private:
  bool settle(std::string& error) {
    const auto ticks = static_cast<int>(std::lround(o_.settle_s / kTickPeriodS));
    for (int k = 0; k < ticks; ++k) rig_.tick();
    if (rig_.task.state() == fw::MotionState::faulted) {
      error = std::string("fault: ") + fw::to_string(rig_.task.fault().reason);
      return false;
    }
    return true;
  }

  HilRig& rig_;
  const ScrewMapOptions& o_;
  std::size_t a_;
  emu::NoiseStream noise_;
};

}  // namespace

std::string validate(const ScrewMapOptions& o) {
  if (!std::isfinite(o.start_mm) || std::fabs(o.start_mm) > 1000.0) return "start_mm must be -1000 .. 1000 mm";
  if (!(o.length_mm > 0.0 && o.length_mm <= 2000.0)) return "length_mm must be > 0 and <= 2000 mm";
  if (!(o.step_mm >= 0.01 && o.step_mm <= o.length_mm)) return "step_mm must be 0.01 mm .. length_mm";
  if (!(o.length_mm / o.step_mm <= 20000.0)) return "length_mm / step_mm must be <= 20000 points";
  if (!(o.overshoot_mm >= 0.0 && o.overshoot_mm <= 100.0)) return "overshoot_mm must be 0 .. 100 mm";
  if (!(o.speed_mm_s > 0.0 && o.speed_mm_s <= 500.0)) return "speed_mm_s must be > 0 and <= 500 mm/s";
  if (!(o.settle_s >= 0.0 && o.settle_s <= 10.0)) return "settle_s must be 0 .. 10 s";
  if (!(o.reference_noise_um_rms >= 0.0 && o.reference_noise_um_rms <= 10.0))
    return "reference_noise_um_rms must be 0 .. 10 um";
  return "";
}

ScrewMapResult run_screw_map(const emu::Scenario& scenario, const fw::FirmwareConfig& config,
                             const ScrewMapOptions& options) {
  ScrewMapResult result;
  if (result.error = validate(options); !result.error.empty()) return result;
  const std::unique_ptr<HilRig> rig = HilRig::create(scenario, config, config.axis[hal::index(options.axis)].controller,
                                                     result.error);
  if (!rig) return result;
  rig->home();
  if (const fw::CommandStatus st = rig->task.hold_position(); st != fw::CommandStatus::ok) {
    result.error = "servo on refused: " + command_status_text(st, rig->task);
    return result;
  }
  MapSession session(*rig, options);
  const auto steps = static_cast<int>(std::floor(options.length_mm / options.step_mm + 1e-9));
  std::string& error = result.error;
  // Forward: from below the first point, every point approached moving +.
  if (!session.move_by(options.start_mm - options.overshoot_mm - session.position_mm(), error)) return result;
  for (int k = 0; k <= steps; ++k)
    if (!session.record_at(options.start_mm + k * options.step_mm, +1, result.points, error)) return result;
  // Back: from above the last point, every point approached moving -.
  if (!session.move_by(options.overshoot_mm, error)) return result;
  for (int k = steps; k >= 0; --k)
    if (!session.record_at(options.start_mm + k * options.step_mm, -1, result.points, error)) return result;
  result.completed = true;
  return result;
}

}  // namespace tnv::hil
