#pragma once
// Host side of BORE_GAUGE / BORE_INFEED (boring on the board, S4): the
// request built and the answer read through the table-driven frame codec.
#include <cstdint>
#include <optional>
#include <string>

#include "firmware/can/frame_codec.hpp"

namespace tnv::can_host {

namespace can = tnv::fw::can;

struct BoreInfeed {
  std::uint8_t tag = 0;
  can::ErrorCode result = can::ErrorCode::ok;
  std::uint8_t detail = 0;  // refused: index of the offending BORE_GAUGE field
  std::uint8_t flags = 0;   // can::BoreFlag bits
  double infeed_top_mm_rev = 0.0;     // at bore.l1_mm
  double infeed_bottom_mm_rev = 0.0;  // at bore.l2_mm
  bool has(can::BoreFlag f) const noexcept { return (flags & f) != 0; }
  int out_of_band() const noexcept { return (has(can::kBoreTopOut) ? 1 : 0) + (has(can::kBoreBottomOut) ? 1 : 0); }
};

// The readings (diametral bore errors, mm) on BORE_GAUGE's 0.1 um grid; an
// empty optional sends "no reading". The caller checks bore_reading_fits().
hal::CanFrame bore_gauge_request(std::uint8_t node, std::uint8_t tag, can::BoreOp op, std::uint16_t part,
                                 std::optional<double> top_mm, std::optional<double> bottom_mm);
BoreInfeed read_bore_infeed(const hal::CanFrame& frame);

// BORE_GAUGE carries the reading (finite, within +-3.2767 mm).
bool bore_reading_fits(double bore_error_mm);

// The name of BORE_GAUGE field `index` ("part", "top", ...), "?" if none.
std::string bore_gauge_field_name(std::uint8_t index);

}  // namespace tnv::can_host
