#pragma once
// Samples of a program run from the node's cyclic telemetry:
// TLM_POSITION_<AXIS> (measured position and reference - position of the
// same tick) of the plane's two axes. The node queues one frame per axis,
// in axis order, every tick; a sample is the plane's first axis' frame and
// the second's that follows it (a second axis' frame without its first is
// dropped: counting began between them). The reference is rebuilt from the
// two rounded 1 nm values (within 1 nm). Z's frame, which follows the
// pair, completes their sample (until it comes a sample has the last Z).
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "tools/can/node_messages.hpp"
#include "tools/score/path_score.hpp"

namespace tnv::can_host {

class PathTelemetry {
 public:
  void take(const hal::CanFrame& frame, can::MessageId id);
  const std::vector<hil::PathSample>& samples() const noexcept { return samples_; }
  // Frames still without a partner (the plane's first axis of a tick whose second has not come).
  std::uint64_t unpaired() const noexcept { return first_ ? 1 : 0; }
  // A HEARTBEAT said frames were dropped (its tx_dropped bit) while samples were taken: ticks are missing.
  bool dropped() const noexcept { return dropped_; }
  // The last reference seen (where the table is held when it rests).
  std::optional<fw::motion::PlanePoint> last_reference() const;

 private:
  // The plane's first axis' position and following (raw 1 nm) of a tick whose second axis has not come yet.
  std::optional<std::array<std::int32_t, 2>> first_;
  std::vector<hil::PathSample> samples_;
  // Z's position and following, raw: its frame comes after the plane's pair and completes their sample.
  std::optional<std::array<std::int32_t, 2>> z_;
  bool z_pending_ = false;  // the last sample waits for its tick's Z
  void set_z(hil::PathSample& s) const;
  bool dropped_ = false;
};

}  // namespace tnv::can_host
