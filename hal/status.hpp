#pragma once
#include <cstdint>

namespace tnv::hal {

// Result of a HAL transfer. Never thrown: the tick path is exception-free.
enum class HalStatus : std::uint8_t {
  ok = 0,
  bus_error,    // transport reported a failed transfer
  timeout,      // transport did not answer in time
  not_present,  // device missing or not opened
  bad_address,  // register window out of range
  output_failed,  // an output line (a servo-enable GPIO) did not take the value written
};

constexpr const char* to_string(HalStatus s) noexcept {
  switch (s) {
    case HalStatus::ok: return "ok";
    case HalStatus::bus_error: return "bus error";
    case HalStatus::timeout: return "timeout";
    case HalStatus::not_present: return "device not present";
    case HalStatus::bad_address: return "bad register address";
    case HalStatus::output_failed: return "output write failed";
  }
  return "unknown";
}

}  // namespace tnv::hal
