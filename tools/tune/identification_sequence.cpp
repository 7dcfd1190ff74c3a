#include "tools/tune/identification_sequence.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "firmware/control/axis_model.hpp"

namespace tnv::tune {

std::vector<fw::ExcitationSpec> identification_steps() {
  std::vector<fw::ExcitationSpec> out;
  for (const double level : {10.0, -10.0, 20.0, -20.0}) {
    fw::ExcitationSpec spec;
    spec.kind = fw::ExcitationKind::step;
    spec.level_mm_s = level;
    spec.duration_s = 0.15;
    spec.settle_s = 0.2;
    out.push_back(spec);
  }
  return out;
}

std::vector<fw::ExcitationSpec> identification_ramps() {
  std::vector<fw::ExcitationSpec> out;
  for (const double level : {10.0, -10.0}) {
    fw::ExcitationSpec spec;
    spec.kind = fw::ExcitationKind::ramp;
    spec.level_mm_s = level;
    spec.rate_mm_s2 = 2.0;
    spec.duration_s = 5.0;
    spec.settle_s = 0.2;
    spec.breakaway_counts = 12;
    out.push_back(spec);
  }
  return out;
}

StepRecord step_record_from(const fw::ExcitationSpec& spec, const std::vector<double>& position_mm,
                            const std::vector<double>& command_mm_s) {
  StepRecord s;
  if (position_mm.empty() || command_mm_s.empty()) return s;
  const auto drive = static_cast<std::size_t>(std::llround(spec.duration_s / fw::kControlPeriod_s));
  s.level_mm_s = command_mm_s.front();
  s.position_mm.assign(position_mm.begin(),
                       position_mm.begin() + static_cast<std::ptrdiff_t>(std::min(drive + 1, position_mm.size())));
  return s;
}

RampRecord ramp_record_from(const std::vector<double>& position_mm, const std::vector<double>& command_mm_s) {
  RampRecord r;
  for (std::size_t j = 1; j < position_mm.size() && j - 1 < command_mm_s.size(); ++j) {
    if (position_mm[j] != position_mm[0]) {
      // position_mm[j] is the first moved reading; the command before it broke the axis away.
      r.broke_away = true;
      r.breakaway_mm_s = command_mm_s[j - 1];
      break;
    }
  }
  return r;
}

}  // namespace tnv::tune
