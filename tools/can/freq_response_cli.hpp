#pragma once
// The frequency-response options both command lines take (`tnvctl
// freq-response`, `tnv-hil freq-response`), registered on their
// subcommand and parsed into FreqResponseOptions. The closed-loop
// experiment's level, tones, carrier and the duration are left unset unless
// given: the active controller's defaults fill them (freq_response_defaults.hpp).
// Built as tnv_freq_response_cli (tools/CMakeLists.txt), not into
// tnv_can_host: the installed host library needs no CLI11.
#include "tools/can/freq_response_run.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace tnv::can_host {

// --loop, --excitation, --plant-level, --loop-level, --duration, --f-min,
// --f-max, --loop-f-min, --loop-f-max, --tones, --loop-tones, --smooth, --carrier.
// `options` must outlive the parse.
void add_freq_response_options(CLI::App& command, FreqResponseOptions& options);

}  // namespace tnv::can_host
