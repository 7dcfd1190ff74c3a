#pragma once
// The per-tick values telemetry and capture send that the TickRecord does
// not hold: the contour error about the running circle's centre and the
// force in newtons.
#include "firmware/can/capture_recorder.hpp"
#include "firmware/can/node_settings.hpp"
#include "firmware/tick/tick_task.hpp"

namespace tnv::fw::can {

// S1 eq. (33) about centre c: | |ref - c| - |pos - c| |, in um. Non-zero only
// on ticks of a circle's motion (motion_tick >= 0), as tnv-hil scores it.
double contour_um(const TickTask& task, const TickRecord& record) noexcept;

// force.n_per_volt x the ADC volts (12-bit unipolar code, 0..10 V: register map).
double force_n(const TickRecord& record, const NodeSettings& settings) noexcept;

TickSignals tick_signals(const TickTask& task, const NodeSettings& settings) noexcept;

}  // namespace tnv::fw::can
