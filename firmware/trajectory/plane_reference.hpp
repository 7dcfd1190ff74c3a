#pragma once
#include <array>

#include "hal/axis.hpp"

namespace tnv::fw {

struct AxisSample {
  double position_mm = 0.0;
  double speed_mm_s = 0.0;
};

// Reference for both axes at one tick.
struct PlaneSample {
  std::array<AxisSample, hal::kAxisCount> axis{};
  double feed_mm_s = 0.0;  // commanded path speed
};

}  // namespace tnv::fw
