#include "tools/hil/homing_json.hpp"

namespace tnv::hil {

nlohmann::json homing_seed_json(const HomingSeedResult& r) {
  return {{"seed", r.seed},
          {"power_up_offset_x_mm", r.power_up_offset_x_mm},
          {"power_up_offset_y_mm", r.power_up_offset_y_mm},
          {"offset_counts_x", r.offset_counts_x},
          {"offset_counts_y", r.offset_counts_y},
          {"homed", r.homed},
          {"failure", r.failure},
          {"home_error_x_um", r.home_error_x_um},
          {"home_error_y_um", r.home_error_y_um},
          {"reading_error_x_um", r.reading_error_x_um},
          {"reading_error_y_um", r.reading_error_y_um},
          {"time_s", r.time_s}};
}

}  // namespace tnv::hil
