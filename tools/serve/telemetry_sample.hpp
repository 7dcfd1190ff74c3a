#pragma once
// One scope sample: the latest value of every telemetry channel when a
// tick's TLM_POSITION_<AXIS> frames have arrived (the node's fastest cyclic
// message), named with its unit as the page shows it. The per-axis
// channels come from the axis list (hal/axis.hpp), kind by kind.
#include <array>
#include <cstddef>
#include <cstdint>

#include "hal/axis.hpp"
#include "tools/can/telemetry_view.hpp"

namespace tnv::serve {

struct ScopeChannel {
  const char* name;  // with the unit: pos_x_mm, following_x_um
  const char* unit;
};

#define TNV_SCOPE_POS(a, ...) {"pos_" #a "_mm", "mm"},
#define TNV_SCOPE_FOLLOWING(a, ...) {"following_" #a "_um", "um"},
#define TNV_SCOPE_S(a, ...) {"s_" #a "_mm_s", "mm/s"},
#define TNV_SCOPE_DHAT(a, ...) {"d_hat_" #a "_mm_s", "mm/s"},
#define TNV_SCOPE_DAC(a, ...) {"dac_" #a "_code", "code"},
inline constexpr auto kScopeChannels = std::to_array<ScopeChannel>({
    TNV_AXES(TNV_SCOPE_POS)
    TNV_AXES(TNV_SCOPE_FOLLOWING)
    TNV_AXES(TNV_SCOPE_S)
    TNV_AXES(TNV_SCOPE_DHAT)
    TNV_AXES(TNV_SCOPE_DAC)
    {"force_n", "N"},
    {"contour_um", "um"},
    {"spindle_rpm", "rpm"},  // measured (TLM_SPINDLE, signed: negative is reverse)
});
#undef TNV_SCOPE_POS
#undef TNV_SCOPE_FOLLOWING
#undef TNV_SCOPE_S
#undef TNV_SCOPE_DHAT
#undef TNV_SCOPE_DAC

struct ScopeSample {
  std::uint64_t seq = 0;  // given by the ring: strictly increasing
  double t_s = 0.0;       // bus clock since the server started
  // NaN for a channel the node does not stream (its tlm.*_ms is 0).
  std::array<double, kScopeChannels.size()> values{};
};

ScopeSample scope_sample(const can_host::TelemetryView& view, double t_s);

}  // namespace tnv::serve
