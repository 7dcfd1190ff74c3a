#pragma once
// What the tick task reports of the last probe move (G38.2-G38.5,
// motion/probe_move.hpp) to the host: how it ended, where the probe
// tripped and where the motion rests (the next element starts there).
#include <array>
#include <cstdint>

#include "firmware/motion/probe_move.hpp"
#include "hal/axis.hpp"

namespace tnv::fw {

struct ProbeReport {
  std::uint32_t count = 0;  // probe outcomes since power-up: a new one is a new report
  motion::ProbeOutcome outcome = motion::ProbeOutcome::none;
  std::uint32_t tag = 0;    // the probe segment's tag (the producer's reference: a streamed program's element number)
  // Tripped: each axis' measured position (table side) in the tick whose
  // snapshot first showed the input changed, so at most one tick's travel
  // past the contact. Otherwise where the motion rests (the end, or the
  // start of a refused probe).
  std::array<double, hal::kAxisCount> trip_mm{};
  std::array<double, hal::kAxisCount> rest_mm{};  // the reference at rest after it
};

}  // namespace tnv::fw
