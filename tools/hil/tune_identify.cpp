#include "tools/hil/tune_identify.hpp"

#include <cstdio>
#include <memory>
#include <vector>

#include "firmware/io/dac_code.hpp"
#include "tools/hil/command_status_text.hpp"
#include "tools/hil/hil_rig.hpp"
#include "tools/tune/identification_sequence.hpp"

namespace tnv::hil {

namespace {

void hold_ticks(HilRig& rig, int ticks) {
  for (int k = 0; k < ticks && rig.task.state() != fw::MotionState::faulted; ++k) rig.tick();
}

// One excitation; positions from the start tick on, and the DAC commands.
bool run_excitation(HilRig& rig, hal::Axis axis, const fw::ExcitationSpec& spec, std::vector<double>& position_mm,
                    std::vector<double>& command_mm_s, std::vector<double>& accel_mm_s2, std::string& error) {
  const std::size_t a = hal::index(axis);
  position_mm.clear();
  command_mm_s.clear();
  accel_mm_s2.clear();
  if (const fw::CommandStatus st = rig.task.start_excitation(axis, spec); st != fw::CommandStatus::ok) {
    error = "start_excitation refused: " + command_status_text(st, rig.task);
    return false;
  }
  const fw::DacScale dac = rig.task.config().axis[a].dac;
  for (int guard = 0; rig.task.exciting() && guard < 20000; ++guard) {
    rig.tick();
    const fw::AxisTickRecord& r = rig.task.last_record().axis[a];
    // This tick's position (the previous command's result) and the command it now applies.
    position_mm.push_back(r.position_mm);
    accel_mm_s2.push_back(r.accel_mm_s2);
    command_mm_s.push_back(fw::dac_code_to_speed_mm_s(r.dac_code, dac));
    if (rig.task.state() == fw::MotionState::faulted) {
      error = std::string("fault during the excitation: ") + fw::to_string(rig.task.fault().reason);
      return false;
    }
  }
  return true;
}

}  // namespace

tune::AxisIdentification identify_axis_on_emulator(const emu::Scenario& scenario, hal::Axis axis) {
  tune::AxisIdentification failed;
  failed.axis = axis;
  std::unique_ptr<HilRig> rig = HilRig::create(scenario, fw::default_firmware_config(), fw::ControllerKind::rdvsc,
                                               failed.error);
  if (!rig) return failed;
  rig->home();
  if (rig->task.hold_position() != fw::CommandStatus::ok) {
    failed.error = "hold_position refused";
    return failed;
  }
  hold_ticks(*rig, 300);
  std::vector<tune::StepRecord> steps;
  std::vector<tune::RampRecord> ramps;
  std::vector<double> pos;
  std::vector<double> cmd;
  std::vector<double> accel;
  for (const fw::ExcitationSpec& spec : tune::identification_steps()) {
    if (!run_excitation(*rig, axis, spec, pos, cmd, accel, failed.error)) return failed;
    steps.push_back(tune::step_record_from(spec, pos, cmd));
    steps.back().accel_mm_s2 = accel;  // the whole excitation: drive and settle
    hold_ticks(*rig, 300);
  }
  for (const fw::ExcitationSpec& spec : tune::identification_ramps()) {
    if (!run_excitation(*rig, axis, spec, pos, cmd, accel, failed.error)) return failed;
    ramps.push_back(tune::ramp_record_from(pos, cmd));
    hold_ticks(*rig, 300);
  }
  return tune::identify_from_records(axis, steps, ramps, kTickPeriodS);
}

std::string mode_fit_text(const tune::ModeFit& fit, double true_hz, double true_zeta) {
  char line[512];
  if (fit.samples == 0) {
    std::snprintf(line, sizeof line, "  structural mode       not looked for (no accelerometer samples)\n");
  } else if (!fit.found) {
    std::snprintf(line, sizeof line, "  structural mode       none found     %s\n", true_hz > 0.0 ? "scenario has one" : "none");
  } else if (true_hz > 0.0) {
    std::snprintf(line, sizeof line,
                  "  mode f (Hz)           %10.4f    %10.4f       %+6.2f %%\n"
                  "  mode zeta             %10.5f    %10.5f       %+6.2f %%\n",
                  fit.freq_hz, true_hz, 100.0 * (fit.freq_hz / true_hz - 1.0), fit.zeta, true_zeta,
                  true_zeta > 0.0 ? 100.0 * (fit.zeta / true_zeta - 1.0) : 0.0);
  } else {
    std::snprintf(line, sizeof line,
                  "  mode f (Hz)           %10.4f    none\n"
                  "  mode zeta             %10.5f    none\n",
                  fit.freq_hz, fit.zeta);
  }
  std::string text = line;
  std::snprintf(line, sizeof line, "  mode fit: ring %.1f mm/s^2, explains %.1f %% of the table-model residual, rms left %.2f mm/s^2%s%s\n",
                fit.ring_amplitude_mm_s2, 100.0 * fit.explained_share, fit.residual_rms_mm_s2,
                fit.note.empty() ? "" : "; ", fit.note.c_str());
  text += line;
  return text;
}

}  // namespace tnv::hil
