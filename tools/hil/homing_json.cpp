#include "tools/hil/homing_json.hpp"

#include <array>
#include <cstddef>
#include <initializer_list>

namespace tnv::hil {

namespace {
constexpr std::string_view kPowerUpOffset = "power_up_offset_*_mm";
constexpr std::string_view kOffsetCounts = "offset_counts_*";
constexpr std::string_view kHomeError = "home_error_*_um";
constexpr std::string_view kReadingError = "reading_error_*_um";

std::vector<std::string> keys_over_axes(std::initializer_list<std::string_view> patterns) {
  std::vector<std::string> out;
  for (const std::string_view p : patterns)
    for (const hal::Axis a : hal::kAxes) out.push_back(axis_key(p, a));
  return out;
}

void put_per_axis(nlohmann::json& j, std::string_view pattern, const std::array<double, hal::kAxisCount>& v) {
  for (const hal::Axis a : hal::kAxes) j[axis_key(pattern, a)] = v[hal::index(a)];
}
}  // namespace

std::string axis_key(std::string_view pattern, hal::Axis axis) {
  std::string out(pattern);
  if (const std::size_t star = out.find('*'); star != std::string::npos) out.replace(star, 1, hal::axis_label(axis));
  return out;
}

std::vector<std::string> homing_start_keys() { return keys_over_axes({kPowerUpOffset, kOffsetCounts}); }
std::vector<std::string> homing_error_keys() { return keys_over_axes({kHomeError, kReadingError}); }

nlohmann::json homing_seed_json(const HomingSeedResult& r) {
  nlohmann::json j = {{"seed", r.seed}, {"homed", r.homed}, {"failure", r.failure}, {"time_s", r.time_s}};
  put_per_axis(j, kPowerUpOffset, r.power_up_offset_mm);
  put_per_axis(j, kOffsetCounts, r.offset_counts);
  put_per_axis(j, kHomeError, r.home_error_um);
  put_per_axis(j, kReadingError, r.reading_error_um);
  return j;
}

}  // namespace tnv::hil
