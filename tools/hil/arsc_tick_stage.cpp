// The test-and-learning stage of `tnv-hil arsc tick` (S3 section 3, Fig. 5,
// at the tick): a separate machine at the start depth cuts a straight
// program with the force loop off while the host drives the feed override
// with a two-level signal; the loop's model is fitted by least squares from
// what the firmware records (force ADC, encoders), never from the scenario.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "tools/hil/arsc_test_stage.hpp"
#include "tools/hil/arsc_tick_study.hpp"
#include "tools/hil/hil_rig.hpp"
#include "tools/hil/program_feeder.hpp"
#include "tools/tune/least_squares.hpp"

namespace tnv::hil {

TickTestStage run_tick_test_stage(const TickStudyConfig& c, std::string& error) {
  TickTestStage fit;
  emu::MillingParams m = c.milling;
  m.depth = {c.milling.depth.start_mm, c.milling.depth.start_mm, 1.0, 1.0};
  emu::Scenario s = study_scenario(c, m);
  s.noise.seed ^= 0x7E57'57A6u;  // a separate cut: its own noise and jitter (inert while [noise] and [io] are off)
  fw::arsc::ArscSourceParams off{};
  off.enabled = false;
  const fw::FirmwareConfig firmware = study_firmware_config(c, off);
  std::unique_ptr<HilRig> rig = ready_study_rig(s, firmware, c, error);
  if (!rig) return fit;
  const StudyProgram program = study_cut_program(c, c.program_feed_mm_s, false);
  ProgramFeeder feeder(program.segments);
  // Two-level feed mean +- step, switching with probability 1/2 every 0.3 s: slower
  // than the axis, comparable to the force's time constant.
  const auto ticks = static_cast<std::size_t>(c.test_stage_s / kTickPeriodS);
  const double mean_feed_mm_s = c.path == StudyPath::stock_step ? c.stock.test_stage_feed_mm_s : c.test_stage_feed_mm_s;
  const std::vector<double> u = test_stage_input(ticks, mean_feed_mm_s, c.test_stage_step_mm_s, 300, 11);
  std::vector<double> f(ticks + 1), v(ticks + 1), x(ticks + 1), y(ticks + 1);
  const auto read = [&](std::size_t k) {
    const fw::TickRecord& rec = rig->task.last_record();
    f[k] = study_force_n(rec, firmware);
    v[k] = std::hypot(rec.axis[0].speed_mm_s, rec.axis[1].speed_mm_s);
    x[k] = rec.axis[0].position_mm;
    y[k] = rec.axis[1].position_mm;
  };
  read(0);
  for (std::size_t k = 0; k < ticks; ++k) {
    if (!feeder.feed(rig->task)) {
      error = std::string("test stage: segment refused: ") + fw::motion::to_string(feeder.last_refusal());
      return fit;
    }
    if (rig->task.set_feed_override(u[k] / c.program_feed_mm_s) != fw::CommandStatus::ok) {
      error = "test stage: feed override refused";
      return fit;
    }
    rig->tick();
    read(k + 1);
  }
  if (rig->task.state() == fw::MotionState::faulted) {
    error = std::string("test stage: firmware fault ") + fw::to_string(rig->task.fault().reason);
    return fit;
  }
  // Drive at the tick: v(k+1) = a v(k) + b u(k-1) (the override set before tick k moves
  // the path point in tick k; the table answers from the next one).
  const std::size_t skip = 50;
  {
    const auto n = static_cast<Eigen::Index>(ticks - skip - 1);
    Eigen::MatrixXd a(n, 2);
    Eigen::VectorXd b(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const std::size_t k = skip + static_cast<std::size_t>(i);
      a(i, 0) = v[k];
      a(i, 1) = u[k - 1];
      b(i) = v[k + 1];
    }
    const Eigen::VectorXd ab = tune::least_squares(a, b).x;
    fit.drive_time_constant_s = -kTickPeriodS / std::log(std::clamp(ab(0), 1e-6, 1.0 - 1e-9));
    fit.drive_gain = ab(1) / (1.0 - ab(0));
    fit.drive_rms_mm_s = std::sqrt((a * ab - b).squaredNorm() / static_cast<double>(n));
  }
  // Force over 10 ms with the mean feed along the path: f(j+1) = a f(j) + b vbar(j).
  {
    const std::size_t step = 10;
    const std::size_t count = (ticks - skip) / step - 1;
    const auto n = static_cast<Eigen::Index>(count);
    Eigen::MatrixXd a(n, 2);
    Eigen::VectorXd b(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const std::size_t k = skip + static_cast<std::size_t>(i) * step;
      a(i, 0) = f[k];
      a(i, 1) = std::hypot(x[k + step] - x[k], y[k + step] - y[k]) / (kTickPeriodS * static_cast<double>(step));
      b(i) = f[k + step];
    }
    const Eigen::VectorXd ab = tune::least_squares(a, b).x;
    const double pole = std::clamp(ab(0), 1e-6, 1.0 - 1e-9);
    fit.force_time_constant_s = -kTickPeriodS * static_cast<double>(step) / std::log(pole);
    fit.cutting_gain_n_per_mm_s = ab(1) / (1.0 - pole);
    fit.force_rms_n = std::sqrt((a * ab - b).squaredNorm() / static_cast<double>(n));
    fit.samples = count;
  }
  return fit;
}

}  // namespace tnv::hil
