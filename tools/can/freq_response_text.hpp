#pragma once
// A frequency-response result as a readable table: frequency, measured gain
// and phase, coherence, the model's gain and phase; then the margins
// measured against the model's.
#include <string>

#include "tools/can/freq_response_run.hpp"

namespace tnv::can_host {

std::string freq_response_text(const FreqResponseResult& result);

}  // namespace tnv::can_host
