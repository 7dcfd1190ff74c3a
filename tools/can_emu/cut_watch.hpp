#pragma once
// What the emulated machine saw of a program's cuts while `tnvctl --emu
// run` streamed it: crashes (the tool in the stock with the spindle
// stopped or slow) and feed moves started before the spindle was at speed,
// judged from the machine's truth (tools/hil/feed_start_judge.hpp), never
// from the firmware's own gate. Off (all zero) on a real bus.
#include <cstdint>
#include <optional>
#include <string>

#include "tools/can/program_wire.hpp"
#include "tools/can_emu/emulated_bus.hpp"
#include "tools/hil/feed_start_judge.hpp"

namespace tnv::can_host {

struct CutJudgement {
  std::uint64_t crashes = 0;
  unsigned feed_before_at_speed = 0;
  unsigned feed_onsets = 0;
  std::optional<std::string> first_crash;  // where and at what spindle speed, when recorded
};

class CutWatch {
 public:
  // `bus`: the emulated bus, or nullptr (a real bus: nothing to watch).
  explicit CutWatch(EmulatedBus* bus);
  ~CutWatch();
  CutWatch(const CutWatch&) = delete;
  CutWatch& operator=(const CutWatch&) = delete;

  bool on() const noexcept { return bus_ != nullptr; }
  // Since construction, for the program as streamed.
  CutJudgement judge(const WireProgram& wire) const;

 private:
  std::uint64_t crashes() const noexcept;

  EmulatedBus* bus_;
  hil::FeedStartJudge judge_;
  std::uint64_t crashes_before_ = 0;
  std::uint64_t done_before_ = 0;
};

}  // namespace tnv::can_host
