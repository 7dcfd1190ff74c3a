#include "emulator/machine.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "emulator/axis_plant.hpp"
#include "emulator/boring_pass.hpp"
#include "emulator/cutting_at_tool.hpp"
#include "emulator/cutting_disturbance.hpp"
#include "emulator/fault_timeline.hpp"
#include "emulator/force_adc.hpp"
#include "emulator/io_board.hpp"
#include "emulator/milling_force.hpp"
#include "emulator/noise_stream.hpp"
#include "emulator/output_transport.hpp"
#include "emulator/quadrature_encoder.hpp"
#include "emulator/scenario_validation.hpp"
#include "emulator/screw_transmission.hpp"
#include "emulator/spindle_drive.hpp"
#include "emulator/spindle_encoder.hpp"
#include "emulator/structural_mode.hpp"
#include "emulator/substep_timing.hpp"
#include "emulator/tool_accelerometer.hpp"
#include "emulator/z_axis_plant.hpp"

namespace tnv::emu {

using hal::Axis;

namespace {
constexpr double kStandardGravityMmS2 = 9806.65;

using AxisStates = std::array<AxisState, hal::kAxisCount>;
using AxisSpeeds = std::array<double, hal::kAxisCount>;

// What each axis carries beyond the table's law (the head's weight and its
// stops on Z: z_axis_plant.hpp). One case per axis and no default: a new
// axis of TNV_AXES states its own.
AxisLoad axis_load(const Scenario& s, Axis axis) noexcept {
  switch (axis) {
    case Axis::x:
    case Axis::y: return AxisLoad{};
    case Axis::z: return z_axis_load(s.z_axis);
  }
  return AxisLoad{};
}
// [noise] drawn for one tick latch, added before the ADCs quantise.
struct SampleNoise {
  double force_v = 0.0;
  std::array<double, hal::kAxisCount> accel_mm_s2{};
};
}  // namespace

struct Machine::Impl {
  explicit Impl(const Scenario& s);

  // Sub-steps up to the next board event (or max_substeps), with the bus
  // outputs constant over the block; true if a tick latched at its end.
  bool run_block(std::uint64_t max_substeps) noexcept;
  void step_substeps(AxisStates& states, const AxisSpeeds& u, std::size_t n) noexcept;
  // n sub-steps of axis i with u and its load held (no cutting, mode or screw
  // in play): the plant's closed form where it holds; sub-step by sub-step
  // from the block's start when the block would end past a stop.
  void advance_held(std::size_t i, AxisState& state, double u_mm_s, std::size_t n) noexcept;
  // The XY table's axes take the cutting force (in their plane) and X the
  // milling force in the sub-step loop; a further axis is stepped there only
  // for its own mode or backlash, over the block in closed form otherwise.
  bool in_substep_loop(std::size_t i) const noexcept {
    const Axis axis = hal::axis_from_index(i);
    return axis == hal::kPlaneFirst || axis == hal::kPlaneSecond || modes[i].enabled() || screws[i].has_backlash();
  }
  TickSamples tick_samples(const SampleNoise* noise = nullptr) const noexcept;
  void step_spindle(std::size_t n) noexcept;
  void follow_spindle_encoder() noexcept;
  // --- [stock] on: cutting where the tool is (emulator/cutting_at_tool.hpp).
  // Every axis and the spindle are stepped one sub-step at a time (a loop
  // of its own, so the machine without a stock keeps step_substeps as it
  // was); per sub-step the tool point's force, from the states at its
  // start, loads the XY axes and the spindle over it.
  void step_substeps_at_tool(AxisStates& states, const AxisSpeeds& u, std::size_t n) noexcept;
  void tool_cut_substep(const AxisStates& states, std::uint64_t at_substep) noexcept;
  double tool_cut_disturbance_mm_s(std::size_t i) const noexcept;
  SampleNoise draw_sample_noise() noexcept;
  void apply_encoder_glitches() noexcept;
  void move_outputs() noexcept;
  void land_due_outputs() noexcept;
  void latch_tick() noexcept;
  double table_mm(std::size_t i) const noexcept {
    const double motor_mm = plants[i].position_mm();
    return screws[i].enabled() ? screws[i].table_mm(motor_mm) : motor_mm;
  }
  std::int64_t encoder_count(std::size_t i) const noexcept;
  // The encoder's index mark: latches the count when the motor side crosses it.
  void watch_index(std::size_t i, double from_mm, double to_mm) noexcept;
  std::uint32_t position_inputs() const noexcept;
  bool probe_touching() const noexcept;
  void apply_due_faults() noexcept;
  void apply_fault_edge(const FaultEdge& edge) noexcept;
  bool any_active(FaultKind kind, std::optional<Axis> axis = std::nullopt) const noexcept;
  std::uint32_t input_bit(const FaultSpec& f) const noexcept;

  // The cutting force is in the XY plane (CuttingVector::component) and the
  // S3 milling force on X, index 0 (tick_samples, step_substeps).
  static_assert(hal::index(hal::kPlaneFirst) == 0, "the milling force acts on axis 0");

  Scenario scenario;
  IoBoard board;
  std::array<AxisPlant, hal::kAxisCount> plants;    // each axis' law ([plant.<axis>])
  std::array<AxisLoad, hal::kAxisCount> loads;      // and what it carries beyond it (axis_load)
  std::array<EndStops, hal::kAxisCount> end_stops;  // from loads (none on X and Y)
  bool any_stops;
  std::array<StructuralMode, hal::kAxisCount> modes;
  std::array<QuadratureEncoder, hal::kAxisCount> encoders;
  CuttingDisturbance cutting;
  MillingForce milling;  // S3 end-milling force on X ([milling], off by default)
  std::array<ScrewTransmission, hal::kAxisCount> screws;  // motor side -> table ([plant] backlash, lead error)
  bool any_mode;
  bool any_backlash;
  SpindleDrive spindle;             // on DAC_SPINDLE and the OUTPUTS spindle bits
  SpindleEncoder spindle_encoder;
  std::unique_ptr<CuttingAtTool> tool_cut;  // [stock] enabled; null otherwise (the table and S1 experiments)
  std::unique_ptr<BoringPass> boring;       // [boring] enabled (with [stock]); null otherwise
  std::uint32_t spindle_encoder_register = 0;  // SPINDLE_ENCODER and SPINDLE_INDEX as the encoder stands
  std::uint32_t spindle_index_register = 0;    // (updated when it moves)

  // [noise] and [io] (seeded; untouched while off).
  bool sample_noise;
  NoiseStream force_noise;
  std::array<NoiseStream, hal::kAxisCount> accel_noise;
  std::array<NoiseStream, hal::kAxisCount> glitch_noise;
  std::array<double, hal::kAxisCount> next_glitch_s{};
  OutputTransport transport;

  std::uint64_t substep = 0;
  std::array<double, hal::kAxisCount> applied_command_mm_s{};  // held during the last sub-step
  CuttingVector applied_cutting{};

  // Injected faults (scenario.faults).
  FaultTimeline fault_timeline;
  std::vector<bool> fault_on;                            // per scheduled fault
  std::array<std::int64_t, hal::kAxisCount> encoder_slip_counts{};  // counts the decoder lost
  std::array<std::optional<std::int64_t>, hal::kAxisCount> dead_encoder_count{};  // frozen count while dead
  std::array<double, hal::kAxisCount> drive_sign = hal::per_axis(1.0);  // -1: runaway (gain sign flipped)

  // Index marks ([board] index_*_deg): motor-side positions index_mm + k lead.
  std::array<double, hal::kAxisCount> index_mm{};
  std::array<std::uint32_t, hal::kAxisCount> index_register{};  // INDEX_X/Y as latched at the last edge
  // The mark interval of the last block's end (watch_index): the next block
  // starts there, so its floor is not computed twice.
  std::array<double, hal::kAxisCount> index_interval_at_mm{};
  std::array<double, hal::kAxisCount> index_interval{};
  std::array<bool, hal::kAxisCount> index_interval_known{};
  bool read_errors = false;
  std::uint64_t ticks_to_sleep = 0;  // missed ticks still to come
};

namespace {
// One element per axis from f(axis).
template <class F>
auto per_axis_from(F f) {
  return [&f]<std::size_t... I>(std::index_sequence<I...>) {
    return std::array{f(hal::axis_from_index(I))...};
  }(std::make_index_sequence<hal::kAxisCount>{});
}
}  // namespace

Machine::Impl::Impl(const Scenario& s)
    : scenario(s),
      board(s.board, s.dac, s.encoder.lead_mm, s.noise, s.spindle),
      plants(per_axis_from([&s](Axis a) { return AxisPlant(s.plant[hal::index(a)]); })),
      loads(per_axis_from([&s](Axis a) { return axis_load(s, a); })),
      end_stops(per_axis_from([this](Axis a) { return EndStops(loads[hal::index(a)]); })),
      any_stops(std::any_of(loads.begin(), loads.end(), [](const AxisLoad& l) { return l.has_stops(); })),
      modes(per_axis_from([&s](Axis a) {
        const AxisPlantParams& p = s.plant[hal::index(a)];
        return StructuralMode(p.mode_hz, p.mode_zeta, kSubstep_s);
      })),
      encoders(per_axis_from([&s](Axis a) { return QuadratureEncoder(s.encoder.count_mm(), s.encoder.offset_counts(a)); })),
      cutting(s.cutting, s.circle.feed_mm_s),
      milling(s.milling, kSubstep_s),
      screws(per_axis_from([&s](Axis a) { return ScrewTransmission(s.plant[hal::index(a)], power_up_position_mm(s, a)); })),
      any_mode(std::any_of(modes.begin(), modes.end(), [](const StructuralMode& m) { return m.enabled(); })),
      any_backlash(std::any_of(screws.begin(), screws.end(), [](const ScrewTransmission& t) { return t.has_backlash(); })),
      spindle(s.spindle),
      spindle_encoder(s.spindle),
      tool_cut(s.stock.enabled ? std::make_unique<CuttingAtTool>(s, kSubstep_s) : nullptr),
      boring(s.stock.enabled && s.boring.enabled
                 ? std::make_unique<BoringPass>(s.boring, s.stock, boring_process_config(s))
                 : nullptr),
      sample_noise(s.noise.any_sample_noise()),
      force_noise(make_noise_stream(s.noise.seed, NoiseStreamId::force_adc)),
      accel_noise(make_axis_noise_streams(s.noise.seed, AxisNoise::accel)),
      glitch_noise(make_axis_noise_streams(s.noise.seed, AxisNoise::glitch)),
      transport(s.io, s.noise.seed),
      fault_timeline(s.faults),
      fault_on(s.faults.size(), false) {
  assert(validate_scenario(s).empty() && "build Machines from validated scenarios");
  // At rest, held by stiction, where power_up_position_mm puts it (the screws' lash starts centred there).
  for (const Axis axis : hal::kAxes) plants[hal::index(axis)].set_state(power_up_position_mm(s, axis), 0.0, true);
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    index_mm[i] = s.encoder.lead_mm * s.board.index_deg(hal::axis_from_index(i)) / 360.0;
  board.preset_snapshot(tick_samples());
  board.defer_outputs(transport.enabled());
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const double rate_per_s = s.noise.encoder_glitch_per_s;
    next_glitch_s[i] =
        rate_per_s > 0.0 ? glitch_noise[i].exponential() / rate_per_s : std::numeric_limits<double>::infinity();
  }
}

std::int64_t Machine::Impl::encoder_count(std::size_t i) const noexcept {
  if (dead_encoder_count[i]) return *dead_encoder_count[i];
  return encoders[i].count(plants[i].position_mm()) + encoder_slip_counts[i];
}

// Marks at index_mm + k lead. Crossing one between two positions latches the
// count the decoder holds at the mark (the encoder reading there, with the
// counts it lost or gained so far), whatever the direction. A block that
// reverses across a mark and back within itself is not seen (blocks are at
// most one tick, and homing crosses marks at constant speed).
void Machine::Impl::watch_index(std::size_t i, double from_mm, double to_mm) noexcept {
  if (from_mm == to_mm) return;  // at rest (a stuck axis, Z in a circle): no mark crossed
  const double lead_mm = scenario.encoder.lead_mm;
  const double k_from = index_interval_known[i] && index_interval_at_mm[i] == from_mm
                            ? index_interval[i]
                            : std::floor((from_mm - index_mm[i]) / lead_mm);
  const double k_to = std::floor((to_mm - index_mm[i]) / lead_mm);
  index_interval_known[i] = true;
  index_interval_at_mm[i] = to_mm;
  index_interval[i] = k_to;
  if (k_from == k_to) return;
  const double mark_mm = index_mm[i] + lead_mm * std::max(k_from, k_to);
  const std::int64_t count =
      dead_encoder_count[i] ? *dead_encoder_count[i] : encoders[i].count(mark_mm) + encoder_slip_counts[i];
  const std::uint32_t edges = ((index_register[i] >> hal::regs::kIndexEdgesShift) + 1u) & hal::regs::kIndexEdgesMask;
  index_register[i] = QuadratureEncoder::wrap(count) | (edges << hal::regs::kIndexEdgesShift);
}

// The switches the table actuates, at the table's position now.
std::uint32_t Machine::Impl::position_inputs() const noexcept {
  using namespace hal::regs;
  const BoardParams& b = scenario.board;
  std::uint32_t bits = 0;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const Axis axis = hal::axis_from_index(i);
    const double table = table_mm(i);
    if (b.home_switch(axis)) {
      const double beyond_mm = (table - b.home_mm(axis)) * b.home_side(axis);
      if (beyond_mm >= 0.0) bits |= axis_registers(axis).input_home;
    }
    if (b.limit_switches) {
      const double min_mm = b.axis[i].limit_min_mm;
      const double max_mm = b.axis[i].limit_max_mm;
      if (table <= min_mm) bits |= axis_registers(axis).input_limit_neg;
      if (table >= max_mm) bits |= axis_registers(axis).input_limit_pos;
    }
  }
  if (probe_touching()) bits |= kInputProbe;
  return bits;
}

// The probe's tip at the tool point (the axes' true positions, the head's
// nose less the tool's length) against the stock the machine cuts
// (CuttingAtTool's); never without a stock. Sampled with the switches at
// each tick latch, so the firmware sees a touch at the first latch after it.
bool Machine::Impl::probe_touching() const noexcept {
  if (!tool_cut) return false;
  return tool_cut->probe_touches(table_mm(hal::index(Axis::x)), table_mm(hal::index(Axis::y)),
                                 tool_point_z_mm(table_mm(hal::index(Axis::z)), scenario.tool));
}

TickSamples Machine::Impl::tick_samples(const SampleNoise* noise) const noexcept {
  TickSamples samples;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) samples.encoder_registers[i] = QuadratureEncoder::wrap(encoder_count(i));
  samples.index_registers = index_register;
  samples.spindle_encoder_register = spindle_encoder_register;
  samples.spindle_index_register = spindle_index_register;
  samples.position_inputs = position_inputs();
  // ADC sample-and-hold: the force held over the sub-step that ends at the tick.
  // (sqrt rather than hypot: no overflow risk at these magnitudes, and cheaper)
  const double magnitude_mm_s = std::sqrt(applied_cutting.x_mm_s * applied_cutting.x_mm_s +
                                          applied_cutting.y_mm_s * applied_cutting.y_mm_s);
  samples.adc_force_code = force_adc_code(magnitude_mm_s, scenario.force_sensor.volts_per_mm_s);
  // With [milling] on, the sensor reads the milling force instead (same ADC scaling law, volts per N).
  if (milling.enabled()) samples.adc_force_code = force_adc_code(milling.force_n(), scenario.force_sensor.volts_per_n);
  // With [stock] on (and [milling] off), the force where the tool is.
  else if (tool_cut) samples.adc_force_code = force_adc_code(tool_cut->force().force_n(), scenario.force_sensor.volts_per_n);
  if (noise != nullptr) {
    const double volts = milling.enabled() ? milling.force_n() * scenario.force_sensor.volts_per_n
                         : tool_cut      ? tool_cut->force().force_n() * scenario.force_sensor.volts_per_n
                                         : magnitude_mm_s * scenario.force_sensor.volts_per_mm_s;
    samples.adc_force_code = force_adc_code_for_volts(volts + noise->force_v);
  }
  // Tool-side accelerometers: table acceleration with the inputs of the
  // sub-step that ends at the tick, plus the mode's deflection acceleration.
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    double process_mm_s = applied_cutting.component(hal::axis_from_index(i)) +
                          (i == 0 && milling.enabled() ? milling.disturbance_mm_s() : 0.0);
    if (tool_cut) process_mm_s += tool_cut_disturbance_mm_s(i);
    // (an axis without a load: exactly the process' disturbance)
    const double disturbance_mm_s =
        loads[i].constant_mm_s != 0.0 ? loads[i].constant_mm_s + process_mm_s : process_mm_s;
    const double table_mm_s2 =
        table_acceleration_mm_s2(plants[i], drive_sign[i] * applied_command_mm_s[i], disturbance_mm_s);
    const double tool_mm_s2 = table_mm_s2 + modes[i].deflection_accel_mm_s2(table_mm_s2);
    samples.adc_accel_codes[i] = accel_adc_code(noise != nullptr ? tool_mm_s2 + noise->accel_mm_s2[i] : tool_mm_s2);
  }
  return samples;
}

SampleNoise Machine::Impl::draw_sample_noise() noexcept {
  const NoiseParams& n = scenario.noise;
  SampleNoise out;
  if (n.force_adc_v_rms > 0.0) out.force_v = n.force_adc_v_rms * force_noise.normal();
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const double random_g = n.accel_g_rms > 0.0 ? n.accel_g_rms * accel_noise[i].normal() : 0.0;
    out.accel_mm_s2[i] = (n.accel_bias_g + random_g) * kStandardGravityMmS2;
  }
  return out;
}

// Poisson miscounts: each one the decoder counts and keeps (docs/scenarios.md
// "Noise"), so applying those due by a latch at that latch is exact.
void Machine::Impl::apply_encoder_glitches() noexcept {
  const NoiseParams& n = scenario.noise;
  const double now_s = substep_time_s(substep);
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    while (next_glitch_s[i] <= now_s) {
      encoder_slip_counts[i] += glitch_noise[i].uniform() < 0.5 ? -n.encoder_glitch_counts : n.encoder_glitch_counts;
      next_glitch_s[i] += glitch_noise[i].exponential() / n.encoder_glitch_per_s;
    }
  }
}

// [io]: the firmware's output writes since the last block go out as one
// transfer; transfers due by now land.
void Machine::Impl::move_outputs() noexcept {
  const std::uint64_t now_clocks = board.elapsed_clocks();
  if (const std::optional<OutputWords> words = board.take_written_outputs()) {
    if (transport.full()) board.land_outputs(transport.take_oldest());
    transport.send(*words, now_clocks);
  }
  land_due_outputs();
}

void Machine::Impl::land_due_outputs() noexcept {
  while (transport.due(board.elapsed_clocks())) board.land_outputs(transport.take_oldest());
}

void Machine::Impl::latch_tick() noexcept {
  if (!sample_noise) {
    board.latch_tick(tick_samples());
  } else {
    apply_encoder_glitches();
    const SampleNoise noise = draw_sample_noise();
    board.latch_tick(tick_samples(&noise));
  }
  if (transport.enabled()) board.set_read_delay_clocks(transport.on_latch(board.elapsed_clocks()));
}

bool Machine::Impl::any_active(FaultKind kind, std::optional<Axis> axis) const noexcept {
  for (std::size_t i = 0; i < fault_on.size(); ++i) {
    const FaultSpec& f = scenario.faults[i];
    if (fault_on[i] && f.kind == kind && (!axis || f.axis == *axis)) return true;
  }
  return false;
}

std::uint32_t Machine::Impl::input_bit(const FaultSpec& f) const noexcept {
  using namespace hal::regs;
  switch (f.kind) {
    case FaultKind::estop: return kInputEstop;
    case FaultKind::servo_alarm: return axis_registers(f.axis).input_alarm;
    case FaultKind::limit_switch:
      return f.positive_side ? axis_registers(f.axis).input_limit_pos : axis_registers(f.axis).input_limit_neg;
    default: return 0;
  }
}

void Machine::Impl::apply_due_faults() noexcept {
  for (const FaultEdge& edge : fault_timeline.take_due(substep)) apply_fault_edge(edge);
}

void Machine::Impl::apply_fault_edge(const FaultEdge& edge) noexcept {
  const FaultSpec& f = scenario.faults[edge.fault];
  const std::size_t i = hal::index(f.axis);
  fault_on[edge.fault] = edge.begins;
  switch (f.kind) {
    case FaultKind::estop:
    case FaultKind::servo_alarm:
    case FaultKind::limit_switch: {
      // Asserted while any scheduled window on this input is open.
      const std::uint32_t bit = input_bit(f);
      bool asserted = false;
      for (std::size_t k = 0; k < fault_on.size(); ++k) asserted = asserted || (fault_on[k] && input_bit(scenario.faults[k]) == bit);
      board.set_input(bit, asserted);
      return;
    }
    case FaultKind::encoder_illegal: {
      // Both channels changed at once: a 180 degree jump the decoder cannot
      // give a direction, so it latches the fault and does not count it.
      // The register then lags the table by 2 counts in the direction of travel.
      board.raise_faults(hal::regs::axis_registers(f.axis).fault_encoder);
      const double v_mm_s = plants[i].speed_mm_s();
      encoder_slip_counts[i] -= v_mm_s > 0.0 ? 2 : v_mm_s < 0.0 ? -2 : 0;
      return;
    }
    case FaultKind::encoder_dead: {
      const bool dead = any_active(FaultKind::encoder_dead, f.axis);
      if (dead && !dead_encoder_count[i]) {
        dead_encoder_count[i] = encoder_count(i);
      } else if (!dead && dead_encoder_count[i]) {
        // The lines come back; the decoder never saw the motion in between.
        const std::int64_t frozen = *dead_encoder_count[i];
        dead_encoder_count[i].reset();
        encoder_slip_counts[i] += frozen - encoder_count(i);
      }
      return;
    }
    case FaultKind::dac_stuck: {
      // The most recent window still open on this axis decides the code.
      std::optional<std::uint32_t> code;
      for (std::size_t k = 0; k < fault_on.size(); ++k) {
        const FaultSpec& g = scenario.faults[k];
        if (fault_on[k] && g.kind == FaultKind::dac_stuck && g.axis == f.axis) code = g.dac_code;
      }
      board.stick_dac(f.axis, code);
      return;
    }
    case FaultKind::missed_tick:
      if (edge.begins) ticks_to_sleep += f.ticks;
      return;
    case FaultKind::late_tick:
      if (edge.begins) {
        const std::uint64_t clocks = static_cast<std::uint64_t>(std::ceil(f.delay_us * 1e-6 * kClockHz - 1e-6));
        board.delay_next_tick((clocks + kSubstepClocks - 1) / kSubstepClocks * kSubstepClocks);
      }
      return;
    case FaultKind::stale_snapshot:
      board.freeze_snapshot(any_active(FaultKind::stale_snapshot));
      return;
    case FaultKind::runaway:
      drive_sign[i] = any_active(FaultKind::runaway, f.axis) ? -1.0 : 1.0;
      return;
    case FaultKind::bus_read_error:
      read_errors = any_active(FaultKind::bus_read_error);
      return;
    case FaultKind::encoder_jump:
      // The register takes the extra counts at once and keeps them: from the
      // next latch on it reads `counts` away from the table.
      if (edge.begins) {
        if (dead_encoder_count[i]) {
          *dead_encoder_count[i] += f.counts;
        } else {
          encoder_slip_counts[i] += f.counts;
        }
      }
      return;
    case FaultKind::snapshot_replayed:
      if (edge.begins) board.replay_next_tick();
      return;
  }
}

bool Machine::Impl::run_block(std::uint64_t max_substeps) noexcept {
  // Bounded so the per-block buffers stay small and on the stack.
  constexpr std::uint64_t kMaxBlock = CuttingDisturbance::kMaxFill;
  static_assert(kMaxBlock <= AxisPlant::kMaxBlock);
  apply_due_faults();  // the next edge is then strictly ahead: never step across it
  if (transport.enabled()) move_outputs();  // likewise the next landing
  const auto n = static_cast<std::size_t>(std::min({board.substeps_to_next_event(), max_substeps, kMaxBlock,
                                                    fault_timeline.substeps_to_next(substep),
                                                    transport.substeps_to_next_landing(board.elapsed_clocks())}));
  // Inputs held over each sub-step, evaluated at its start.
  AxisSpeeds u{};
  AxisStates states{};
  AxisSpeeds from_mm{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    applied_command_mm_s[i] = board.command_mm_s(hal::axis_from_index(i));
    // The drive's gain sign (runaway fault: -1) acts on what the servopack is told.
    u[i] = drive_sign[i] * applied_command_mm_s[i];
    states[i] = plants[i].state();  // local state: independent chains, no memory round trips
    from_mm[i] = states[i].position_mm;
  }
  if (tool_cut) {
    step_substeps_at_tool(states, u, n);
  } else if (cutting.enabled() || milling.enabled() || any_mode || any_backlash) {
    step_substeps(states, u, n);
  } else {
    // Held inputs: the closed form where it is provably the same as
    // stepping, sub-steps elsewhere (AxisPlant::advance_held).
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) advance_held(i, states[i], u[i], n);
  }
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    plants[i].set_state(states[i]);
    watch_index(i, from_mm[i], states[i].position_mm);
  }
  if (!tool_cut) step_spindle(n);  // with a tool cut: in step_substeps_at_tool, loaded
  substep += n;
  const bool tick_due = board.advance_substeps(n);
  if (transport.enabled()) land_due_outputs();  // landing at a latch: before it samples
  if (!tick_due) return false;
  latch_tick();
  return true;
}

// The spindle over a block, its inputs held like the axes'. Disabled and
// at rest it costs two compares (the circle experiment's case).
void Machine::Impl::step_spindle(std::size_t n) noexcept {
  const bool enabled = board.spindle_enabled();
  if (!enabled && spindle.at_rest()) return;  // disabled, its command is 0 whatever the DAC holds
  spindle.set_inputs(board.spindle_dac_output_code(), enabled, board.spindle_reverse());
  if (spindle.at_rest()) return;
  spindle.advance_unloaded(n);
  follow_spindle_encoder();
}

void Machine::Impl::follow_spindle_encoder() noexcept {
  // A block is at most one tick: 0.2 rev at 12,000 rpm, so at most one index mark.
  spindle_encoder.follow(spindle.revolutions());
  spindle_encoder_register = QuadratureEncoder::wrap(spindle_encoder.count());
  const auto edges = static_cast<std::uint32_t>(spindle_encoder.index_edges() & hal::regs::kIndexEdgesMask);
  spindle_index_register =
      QuadratureEncoder::wrap(spindle_encoder.latched_count()) | (edges << hal::regs::kIndexEdgesShift);
}

// A stop inside a block is met at its sub-step: the block is redone one
// sub-step at a time from its start (rare: only a head driven into a stop).
void Machine::Impl::advance_held(std::size_t i, AxisState& state, double u_mm_s, std::size_t n) noexcept {
  const AxisState from = state;
  const double load_mm_s = loads[i].constant_mm_s;
  plants[i].advance_held(state, u_mm_s, load_mm_s, n);
  if (!any_stops || !end_stops[i].beyond(state)) {
    if (any_stops) end_stops[i].apply(state);  // leaving a stop re-arms its count
    return;
  }
  state = from;
  for (std::size_t k = 0; k < n; ++k) {
    plants[i].advance(state, u_mm_s, load_mm_s);
    end_stops[i].apply(state);
  }
}

// The cutting and milling forces depend on the table's speed at the start
// of each sub-step, the modes need every sub-step's table acceleration and
// the backlash every sub-step's position: no closed form over the block,
// one sub-step at a time.
void Machine::Impl::step_substeps(AxisStates& states, const AxisSpeeds& u, std::size_t n) noexcept {
  double load_per_speed[CuttingDisturbance::kMaxFill];
  cutting.fill_load_per_speed(substep, n, load_per_speed);
  // Locals: the chains stay in registers (nothing here can alias them).
  AxisStates s = states;
  std::array<ModeState, hal::kAxisCount> mode_states{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) mode_states[i] = modes[i].state();
  CuttingVector cut{};
  constexpr auto kPerSubstep = static_cast<double>(kSubstepsPerSecond);
  constexpr std::size_t kX = hal::index(hal::kPlaneFirst), kY = hal::index(hal::kPlaneSecond);
  const bool cutting_on = cutting.enabled();
  std::array<bool, hal::kAxisCount> in_loop{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    in_loop[i] = in_substep_loop(i);
    if (!in_loop[i]) advance_held(i, s[i], u[i], n);
  }
  for (std::size_t k = 0; k < n; ++k) {
    AxisSpeeds v0{};
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) v0[i] = s[i].speed_mm_s;
    if (cutting_on) cut = CuttingDisturbance::force(load_per_speed[k], v0[kX], v0[kY]);
    const double milling_x_mm_s = milling.enabled() ? milling.disturbance_mm_s() : 0.0;
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      if (!in_loop[i]) continue;
      // X: the cutting and the milling force; Y: the cutting force (as
      // before Z: the same sums, bit for bit); a further axis: its load.
      const double d_mm_s = i == kX ? cut.x_mm_s + milling_x_mm_s : i == kY ? cut.y_mm_s : loads[i].constant_mm_s;
      plants[i].advance(s[i], u[i], d_mm_s);
      if (any_stops) end_stops[i].apply(s[i]);
    }
    if (milling.enabled()) milling.advance(v0[0], substep_time_s(substep + k));
    if (any_mode)
      for (std::size_t i = 0; i < hal::kAxisCount; ++i)
        if (in_loop[i]) modes[i].advance(mode_states[i], (s[i].speed_mm_s - v0[i]) * kPerSubstep);
    if (any_backlash)
      for (std::size_t i = 0; i < hal::kAxisCount; ++i)
        if (in_loop[i]) screws[i].follow(s[i].position_mm);
  }
  states = s;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) modes[i].set_state(mode_states[i]);
  applied_cutting = cut;  // the last sub-step's: what the force sensor and truth() see
}

// --- cutting where the tool is ([stock] on) ---------------------------------

// step_substeps with the tool's process in it: every axis in the loop (Z's
// position makes the depth of cut), the spindle stepped with its load. The
// spindle's inputs are the block's, as step_spindle() takes them.
void Machine::Impl::step_substeps_at_tool(AxisStates& states, const AxisSpeeds& u, std::size_t n) noexcept {
  double load_per_speed[CuttingDisturbance::kMaxFill];
  cutting.fill_load_per_speed(substep, n, load_per_speed);
  const bool enabled = board.spindle_enabled();
  if (enabled || !spindle.at_rest()) spindle.set_inputs(board.spindle_dac_output_code(), enabled, board.spindle_reverse());
  AxisStates s = states;
  std::array<ModeState, hal::kAxisCount> mode_states{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) mode_states[i] = modes[i].state();
  CuttingVector cut{};
  constexpr auto kPerSubstep = static_cast<double>(kSubstepsPerSecond);
  constexpr std::size_t kX = hal::index(hal::kPlaneFirst), kY = hal::index(hal::kPlaneSecond);
  for (std::size_t k = 0; k < n; ++k) {
    const AxisStates at = s;  // the sub-step's start: the inputs held over it
    if (cutting.enabled()) cut = CuttingDisturbance::force(load_per_speed[k], at[kX].speed_mm_s, at[kY].speed_mm_s);
    const double milling_x_mm_s = milling.enabled() ? milling.disturbance_mm_s() : 0.0;
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      const double d_mm_s = (i == kX ? cut.x_mm_s + milling_x_mm_s : i == kY ? cut.y_mm_s : loads[i].constant_mm_s) +
                            tool_cut_disturbance_mm_s(i);
      plants[i].advance(s[i], u[i], d_mm_s);
      if (any_stops) end_stops[i].apply(s[i]);
    }
    if (milling.enabled()) milling.advance(at[0].speed_mm_s, substep_time_s(substep + k));
    tool_cut_substep(at, substep + k);
    if (any_mode)
      for (std::size_t i = 0; i < hal::kAxisCount; ++i)
        modes[i].advance(mode_states[i], (s[i].speed_mm_s - at[i].speed_mm_s) * kPerSubstep);
    if (any_backlash)
      for (std::size_t i = 0; i < hal::kAxisCount; ++i) screws[i].follow(s[i].position_mm);
  }
  states = s;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) modes[i].set_state(mode_states[i]);
  applied_cutting = cut;
  spindle.settle_if_stopping();
  if (!spindle.at_rest()) follow_spindle_encoder();
}

// One sub-step of the process from the states at its start: the tool point
// is the table's X and Y and the spindle nose's Z less the tool's length;
// the force it has then loads the spindle over the sub-step (the XY axes
// take it in step_substeps_at_tool through tool_cut_disturbance_mm_s).
void Machine::Impl::tool_cut_substep(const AxisStates& at, std::uint64_t at_substep) noexcept {
  constexpr std::size_t kX = hal::index(hal::kPlaneFirst), kY = hal::index(hal::kPlaneSecond);
  constexpr std::size_t kZ = hal::index(Axis::z);
  const auto table_at = [this, &at](std::size_t i) {
    return screws[i].enabled() ? screws[i].table_mm(at[i].position_mm) : at[i].position_mm;
  };
  const double spindle_rpm = spindle.speed_rpm();
  const double load_n = tool_cut->force().force_n();
  const double tool_z_mm = tool_point_z_mm(table_at(kZ), scenario.tool);
  // The boring bar deflects with the tool point's depth and the head's feed per spindle revolution.
  if (boring) boring->advance(tool_z_mm, at[kZ].speed_mm_s, spindle_rpm);
  tool_cut->advance(ToolPointMotion{.x_mm = table_at(kX),
                                    .y_mm = table_at(kY),
                                    .z_mm = tool_z_mm,
                                    .vx_mm_s = at[kX].speed_mm_s,
                                    .vy_mm_s = at[kY].speed_mm_s},
                    spindle_rpm, spindle.commanded_rpm(), substep_time_s(at_substep));
  if (!spindle.at_rest()) spindle.step(load_n);
}

double Machine::Impl::tool_cut_disturbance_mm_s(std::size_t i) const noexcept {
  const Axis axis = hal::axis_from_index(i);
  if (axis == hal::kPlaneFirst) return tool_cut->force().disturbance_x_mm_s();
  if (axis == hal::kPlaneSecond) return tool_cut->force().disturbance_y_mm_s();
  return 0.0;
}


Machine::Machine(const Scenario& scenario) : impl_(std::make_unique<Impl>(scenario)) {}
Machine::~Machine() = default;

bool Machine::read_register(std::uint16_t word, std::uint32_t& value) noexcept {
  if (impl_->read_errors) return false;
  return impl_->board.read_register(word, value);
}

bool Machine::read_registers(std::uint16_t first_word, std::span<std::uint32_t> values) noexcept {
  if (impl_->read_errors) return false;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!impl_->board.read_register(static_cast<std::uint16_t>(first_word + i), values[i])) return false;
  }
  return true;
}

bool Machine::write_register(std::uint16_t word, std::uint32_t value) noexcept {
  return impl_->board.write_register(word, value);
}

bool Machine::write_registers(std::uint16_t first_word, std::span<const std::uint32_t> values) noexcept {
  if (values.size() > 0x10000u - first_word) return false;  // would wrap past the last word
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!impl_->board.accepts_write(static_cast<std::uint16_t>(first_word + i), values[i])) return false;
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    impl_->board.write_register(static_cast<std::uint16_t>(first_word + i), values[i]);
  }
  return true;
}

void Machine::advance_to_next_tick() noexcept {
  for (;;) {
    while (!impl_->run_block(std::numeric_limits<std::uint64_t>::max())) {
    }
    if (impl_->ticks_to_sleep == 0) return;
    --impl_->ticks_to_sleep;  // a lost tick interrupt: the firmware sleeps through this latch
  }
}

void Machine::advance_clocks(std::uint64_t clocks) noexcept {
  const std::uint64_t end = impl_->substep + (clocks + kSubstepClocks - 1) / kSubstepClocks;
  while (impl_->substep < end) impl_->run_block(end - impl_->substep);
}

void Machine::set_firmware_work_ns(double work_ns) noexcept { impl_->transport.set_work_ns(work_ns); }

std::uint64_t Machine::elapsed_clocks() const noexcept { return impl_->board.elapsed_clocks(); }

double Machine::time_s() const noexcept { return substep_time_s(impl_->substep); }

AxisTruth Machine::truth(Axis axis) const noexcept {
  const std::size_t i = hal::index(axis);
  const AxisPlant& plant = impl_->plants[i];
  const double table_mm = impl_->table_mm(i);
  return AxisTruth{.position_mm = table_mm,
                   .speed_mm_s = plant.speed_mm_s(),
                   .tool_position_mm = table_mm + impl_->modes[i].deflection_mm(),
                   .motor_position_mm = plant.position_mm(),
                   .command_mm_s = impl_->applied_command_mm_s[i],
                   .cutting_mm_s = impl_->tool_cut ? impl_->applied_cutting.component(axis) +
                                                         impl_->tool_cut_disturbance_mm_s(i)
                                                   : impl_->applied_cutting.component(axis),
                   .stuck = plant.stuck(),
                   .dac_output_code = impl_->board.dac_output_code(axis)};
}

SpindleTruth Machine::spindle_truth() const noexcept {
  const SpindleDrive& drive = impl_->spindle;
  return SpindleTruth{.speed_rpm = drive.speed_rpm(),
                      .revolutions = drive.revolutions(),
                      .command_rpm = drive.commanded_rpm(),
                      .at_rest = drive.at_rest()};
}

BoardOutputs Machine::board_outputs() const noexcept {
  const IoBoard& board = impl_->board;
  BoardOutputs out;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const Axis axis = hal::axis_from_index(i);
    out.dac_register[i] = board.dac_register(axis);
    out.dac_output[i] = board.dac_output_code(axis);
    out.enabled[i] = board.enabled(axis);
  }
  out.watchdog_tripped = board.watchdog_tripped();
  out.spindle_dac_register = board.spindle_dac_register();
  out.spindle_dac_mid_code = board.spindle_dac_mid_code();
  out.spindle_enabled = board.spindle_enabled();
  if (const auto trip = board.last_watchdog_trip_clocks()) {
    out.watchdog_trip_s = static_cast<double>(*trip) / static_cast<double>(kClockHz);
  }
  return out;
}

std::uint32_t Machine::dac_mid_code() const noexcept { return impl_->board.dac().mid_code(); }

double Machine::index_mark_mm(Axis axis) const noexcept { return impl_->index_mm[hal::index(axis)]; }

const Scenario& Machine::scenario() const noexcept { return impl_->scenario; }

double Machine::milling_force_n() const noexcept { return impl_->milling.force_n(); }

double Machine::milling_depth_mm() const noexcept { return impl_->milling.depth_mm(time_s()); }

const CuttingAtTool* Machine::cutting_at_tool() const noexcept { return impl_->tool_cut.get(); }
BoringPass* Machine::boring_pass() noexcept { return impl_->boring.get(); }
const BoringPass* Machine::boring_pass() const noexcept { return impl_->boring.get(); }

bool Machine::fault_active(std::size_t i) const noexcept {
  return i < impl_->fault_on.size() && impl_->fault_on[i];
}

void Machine::set_estop(bool asserted) noexcept { impl_->board.set_input(hal::regs::kInputEstop, asserted); }

void Machine::set_servo_alarm(Axis axis, bool asserted) noexcept {
  impl_->board.set_input(hal::regs::axis_registers(axis).input_alarm, asserted);
}

void Machine::set_limit(Axis axis, bool positive_side, bool asserted) noexcept {
  const hal::regs::AxisRegisters& r = hal::regs::axis_registers(axis);
  impl_->board.set_input(positive_side ? r.input_limit_pos : r.input_limit_neg, asserted);
}

}  // namespace tnv::emu
