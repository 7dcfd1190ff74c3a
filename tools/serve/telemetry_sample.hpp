#pragma once
// One scope sample: the latest value of every telemetry channel when a
// TLM_POSITION frame arrived (the node's fastest cyclic message), named
// with its unit as the page shows it.
#include <array>
#include <cstddef>
#include <cstdint>

#include "tools/can/telemetry_view.hpp"

namespace tnv::serve {

struct ScopeChannel {
  const char* name;  // with the unit: pos_x_mm, following_x_um
  const char* unit;
};

inline constexpr std::array<ScopeChannel, 12> kScopeChannels{{
    {"pos_x_mm", "mm"},
    {"pos_y_mm", "mm"},
    {"following_x_um", "um"},
    {"following_y_um", "um"},
    {"s_x_mm_s", "mm/s"},
    {"s_y_mm_s", "mm/s"},
    {"d_hat_x_mm_s", "mm/s"},
    {"d_hat_y_mm_s", "mm/s"},
    {"dac_x_code", "code"},
    {"dac_y_code", "code"},
    {"force_n", "N"},
    {"contour_um", "um"},
}};

struct ScopeSample {
  std::uint64_t seq = 0;  // given by the ring: strictly increasing
  double t_s = 0.0;       // bus clock since the server started
  // NaN for a channel the node does not stream (its tlm.*_ms is 0).
  std::array<double, kScopeChannels.size()> values{};
};

ScopeSample scope_sample(const can_host::TelemetryView& view, double t_s);

}  // namespace tnv::serve
