#include "tools/can_emu/cut_watch.hpp"

#include <cstdio>
#include <vector>

#include "emulator/cutting_at_tool.hpp"

namespace tnv::can_host {

CutWatch::CutWatch(EmulatedBus* bus) : bus_(bus) {
  if (bus_ == nullptr) return;
  const hil::HilRig& rig = bus_->rig();
  crashes_before_ = crashes();
  done_before_ = rig.task.motion().stats().segments_done;
  bus_->set_step_observer([this, &rig] {
    judge_.observe(rig.machine, static_cast<std::size_t>(rig.task.motion().stats().segments_done - done_before_));
  });
}

CutWatch::~CutWatch() {
  if (bus_ != nullptr) bus_->set_step_observer({});
}

std::uint64_t CutWatch::crashes() const noexcept {
  const emu::CuttingAtTool* cut = bus_ != nullptr ? bus_->rig().machine.cutting_at_tool() : nullptr;
  return cut != nullptr ? cut->crashes().count() - crashes_before_ : 0;
}

CutJudgement CutWatch::judge(const WireProgram& wire) const {
  CutJudgement j;
  if (bus_ == nullptr) return j;
  std::vector<fw::motion::Segment> elements;
  elements.reserve(wire.elements.size());
  for (const WireElement& e : wire.elements) elements.push_back(e.segment);
  const hil::FeedStartCount starts = judge_.count(elements);
  j.crashes = crashes();
  j.feed_before_at_speed = starts.feed_before_at_speed;
  j.feed_onsets = starts.feed_onsets;
  const emu::CuttingAtTool* cut = bus_->rig().machine.cutting_at_tool();
  if (cut != nullptr && j.crashes > 0 && crashes_before_ < emu::SpindleCrashLog::kKept) {
    const emu::CrashEvent& e = cut->crashes().event(static_cast<std::size_t>(crashes_before_));
    char buf[160];
    std::snprintf(buf, sizeof buf, "at (%.3f, %.3f, %.3f) mm, spindle %.0f rpm of %.0f commanded", e.x_mm, e.y_mm, e.z_mm,
                  e.spindle_rpm, e.commanded_rpm);
    j.first_crash = buf;
  }
  return j;
}

}  // namespace tnv::can_host
