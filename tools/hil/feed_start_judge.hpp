#pragma once
// The spindle's rule for a cut, judged from the machine (issue 27): "while
// the spindle is commanded on, a feed move starts only once it is at
// speed". The firmware's own gate says this never happens, so it is
// counted from the emulator's truth, not from the firmware's record:
//  - a feed move begins when the tool point's real XYZ speed passes
//    kMovingMmS after it was at rest (below kRestMmS) and the tool then
//    goes on to leave that point by more than kLeftRestMm before it is at
//    rest again (a servo's sub-micron twitch at rest, as after a rapid
//    while the next feed waits for the spindle, starts nothing); the
//    element at the front of the motion queue when the speed passed says
//    whether it is a feed move (the program's own list: a rapid may start
//    while the spindle runs up), and the spindle is judged then too;
//  - the spindle is commanded on when the drive's speed command (what its
//    DAC and enable give it) is not zero, and at speed when that command
//    has not changed for kSteadyTicks (the firmware's ramp is over) and the
//    drive's real speed is within the firmware's default window of it
//    (5 % or 20 rpm, within_at_speed_window).
// tnv-hil path, tnvctl --emu run and tnv-hil spindle-safety count with it.
// Crashes (the stock engaged with a stopped or slow spindle) are the
// emulator's own log (emu::CuttingAtTool), read by the caller.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "emulator/machine.hpp"
#include "firmware/motion/segment.hpp"
#include "hal/axis.hpp"

namespace tnv::hil {

// The firmware's default at-speed window (spindle.at_speed_fraction 5 %,
// floor 20 rpm) around `command_rpm`, whatever the firmware under test uses.
bool within_at_speed_window(double speed_rpm, double command_rpm) noexcept;

// A start of motion from rest, as the machine saw it.
struct MotionOnset {
  std::size_t front = 0;       // the element at the front of the queue then (elements done)
  bool spindle_ready = false;  // commanded off, or on and at speed (FeedStartJudge::spindle_ready)
};

struct FeedStartCount {
  std::uint32_t feed_onsets = 0;           // onsets whose element is a feed move
  std::uint32_t feed_before_at_speed = 0;  // ... of them with the spindle commanded on and not at speed
};

class FeedStartJudge {
 public:
  static constexpr double kMovingMmS = 0.5;
  static constexpr double kRestMmS = 0.05;
  static constexpr std::uint32_t kSteadyTicks = 10;
  // 24 encoder counts: a move, not a twitch (measured: 0.6 um twitches, moves of 2.4 mm and more).
  static constexpr double kLeftRestMm = 0.01;

  // Once per tick, after the machine advanced; `front` is the index, in the
  // program's element list, of the element at the front of the queue.
  void observe(const emu::Machine& machine, std::size_t front);

  // The onsets judged against the elements the queue ran, in its order
  // (the parsed program's, or the wire's when it was streamed).
  FeedStartCount count(const std::vector<fw::motion::Segment>& elements) const noexcept;
  const std::vector<MotionOnset>& onsets() const noexcept { return onsets_; }
  // The drive's command and real speed would pass as at speed now.
  bool spindle_ready(const emu::Machine& machine) const noexcept;

 private:
  bool was_moving_ = false;
  std::optional<MotionOnset> pending_;           // passed kMovingMmS, not yet kLeftRestMm from there
  std::array<double, hal::kAxisCount> from_mm_{};  // where the speed passed kMovingMmS
  double last_command_rpm_ = 0.0;
  std::uint32_t steady_ticks_ = 0;
  std::vector<MotionOnset> onsets_;
};

}  // namespace tnv::hil
