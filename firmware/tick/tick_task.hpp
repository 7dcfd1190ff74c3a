#pragma once
// The 1 ms control tick (design notes "The tick"): read the latched
// snapshot -> M-method speed over the measured period -> trajectory ->
// axis controllers -> DAC codes -> supervisor -> write outputs -> kick the
// watchdog. Fixed cost: no allocation, no exceptions, no locks, no system
// calls. Commands are accepted between ticks only.
#include <array>
#include <cstdint>

#include "firmware/control/pid_controller.hpp"
#include "firmware/control/rdvsc_controller.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/tick_record.hpp"
#include "firmware/timing/encoder_position.hpp"
#include "firmware/trajectory/circle_trajectory.hpp"
#include "hal/io_board.hpp"

namespace tnv::fw {

enum class CommandStatus : std::uint8_t {
  ok = 0,
  busy,     // not allowed in the current motion state (e.g. while moving)
  faulted,  // a fault is latched: clear it first
  invalid,  // a parameter is out of range or non-finite
  cause_present,  // clear_fault refused: the fault's cause is still asserted
};

constexpr const char* to_string(CommandStatus s) noexcept {
  switch (s) {
    case CommandStatus::ok: return "ok";
    case CommandStatus::busy: return "busy";
    case CommandStatus::faulted: return "faulted";
    case CommandStatus::invalid: return "invalid";
    case CommandStatus::cause_present: return "cause_present";
  }
  return "?";
}

class TickTask {
 public:
  // config must have passed validate(config); the task keeps a copy.
  TickTask(hal::IoBoard& board, const FirmwareConfig& config) noexcept;
  TickTask(const TickTask&) = delete;
  TickTask& operator=(const TickTask&) = delete;

  void tick() noexcept;

  // --- commands (between ticks)
  CommandStatus start_circle(const CircleSpec& spec) noexcept;
  CommandStatus select_controller(hal::Axis axis, ControllerKind kind) noexcept;
  CommandStatus disable() noexcept;
  CommandStatus clear_fault() noexcept;

  // --- status
  const TickRecord& last_record() const noexcept { return record_; }
  const FaultRecord& fault() const noexcept { return fault_; }
  const TickCounters& counters() const noexcept { return counters_; }
  MotionState state() const noexcept { return state_; }
  ControllerKind controller(hal::Axis axis) const noexcept { return axis_[hal::index(axis)].kind; }
  const FirmwareConfig& config() const noexcept { return config_; }
  // Ticks from the start of motion to the end of the trajectory (inclusive).
  std::int64_t motion_ticks() const noexcept { return motion_ticks_; }

 private:
  struct AxisLoop {
    AxisLoop(const AxisConfig& config) noexcept;
    PidController pid;
    RdvscController dvsc;
    RdvscController rdvsc;
    ControllerKind kind;
    EncoderPosition encoder;
    double speed_mm_s = 0.0;
    AxisController& active() noexcept;
  };

  void read_timebase(bool bus_ok, std::uint32_t& ticks_missed, bool& advanced) noexcept;
  void update_reference() noexcept;
  void set_reference(std::size_t i, const AxisSample& now, const AxisSample& next) noexcept;
  bool servo_on() const noexcept;
  void latch_fault(const FaultRecord& f) noexcept;

  hal::IoBoard& board_;
  FirmwareConfig config_;
  std::array<AxisLoop, hal::kAxisCount> axis_;
  CircleTrajectory circle_{};
  std::int64_t dwell_ticks_ = 0;
  std::int64_t motion_ticks_ = 0;
  std::int64_t phase_tick_ = 0;  // ticks into the current dwell / motion phase
  std::array<AxisSample, hal::kAxisCount> hold_{};  // reference while dwelling / holding
  std::array<AxisSample, hal::kAxisCount> next_{};  // x_ref,k+1
  MotionState state_ = MotionState::disabled;
  FaultRecord fault_{};
  TickCounters counters_{};
  TickRecord record_{};
  hal::DiscreteInputs last_inputs_{};
  bool first_tick_ = true;
  std::uint32_t last_sequence_ = 0;
  std::uint32_t last_clock_ = 0;
};

}  // namespace tnv::fw
