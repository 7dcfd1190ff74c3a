#pragma once
// Frequency response on the target (docs/frequency-response.md), each
// experiment an EXCITE recorded by the node's capture at every tick
// (position, command, DAC code, excitation), uploaded and estimated on the
// host (tools/tune):
//  - closed loop (always): multisine or sweep added to the command of the
//    controller holding the axis; gives the open and closed loop, and the
//    margins (read off the measured open loop);
//  - plant (--loop plant): an open-loop multisine as the command itself
//    (inside the stiff loop the plant input is too small at low frequency
//    for the DAC's resolution; the doc has the numbers).
// The same code runs on SocketCAN and on the emulated controller.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "firmware/compensation/excitation.hpp"
#include "firmware/control/axis_model.hpp"
#include "hal/axis.hpp"
#include "tools/can/node_client.hpp"
#include "tools/tune/bode_margins.hpp"
#include "tools/tune/freq_response.hpp"
#include "tools/tune/freq_response_model.hpp"

namespace tnv::can_host {

struct FreqResponseOptions {
  tune::LoopKind loop = tune::LoopKind::plant;
  // The closed-loop experiment (open / closed loop, margins): multisine or sweep.
  fw::ExcitationKind kind = fw::ExcitationKind::multisine;
  // Unset (nullopt): the active controller's default (freq_response_defaults.hpp).
  double plant_level_mm_s = 10.0;  // open-loop multisine of the plant: RMS x sqrt(2)
  std::optional<double> loop_level_mm_s;  // closed-loop excitation: sweep amplitude / multisine RMS x sqrt(2)
  std::optional<double> duration_s;       // each experiment's record; a multisine's whole periods of 1 / f_min
  double f_min_hz = 1.0;
  double f_max_hz = 100.0;         // the plant experiment's band
  double loop_f_min_hz = 10.0;     // the closed-loop experiment's band: below, the stiff loop leaves the
                                   // plant input under the DAC's resolution (docs/frequency-response.md)
  double loop_f_max_hz = 450.0;    // ... up to the phase crossover
  std::uint32_t tones = 40;        // the plant experiment's tones
  std::optional<std::uint32_t> loop_tones;  // the closed-loop experiment's tones (a sweep's points)
  int skip_periods = 1;            // multisine: periods dropped as the transient
  // Margins and bandwidth are read off the measured points smoothed over
  // this many tones each side (tools/tune/freq_response_smoothing.hpp); 0:
  // off. The points printed are the raw ones.
  int smooth_half_window = 3;
  // The closed-loop experiment's carrier (excite.carrier_mm_s): the holding
  // reference moves at this speed while the excitation runs, so the
  // encoder's quantisation decorrelates from the excitation and the table
  // never reverses; 0 = a standing table. The run goes the other way when
  // the soft limits leave no room ahead, and moves the table back after.
  std::optional<double> carrier_mm_s;
  // The plant the model side uses: the emulated table's exact ZOH when
  // known (tnv-hil, --emu); otherwise the node's configured model.
  std::optional<fw::AxisModel> plant_model;
};

// The options' own checks (ranges as the node's, plus the capture's room
// for 4 channels), with the unset ones at every controller's defaults; ""
// when fine, else the first problem naming the option.
std::string check_options(const FreqResponseOptions& options);

struct FreqResponsePoint {
  double freq_hz = 0.0;
  std::complex<double> measured;  // of the chosen loop
  double coherence = 0.0;
  std::complex<double> model;     // the implemented-loop model's (plant: the plant model's)
};

struct FreqResponseResult {
  hal::Axis axis = hal::Axis::x;
  tune::LoopKind loop = tune::LoopKind::plant;
  fw::ExcitationKind kind = fw::ExcitationKind::multisine;
  std::string controller;          // "pid", "dvsc", "rdvsc"
  std::string plant_model;         // what the model side used, in words
  FreqResponseOptions options;     // as run: every default filled in (the carrier's sign as it went)
  std::vector<FreqResponsePoint> points;
  tune::BodeMargins margins;       // measured open loop
  double bandwidth_hz = 0.0;       // measured closed loop, -3 dB (NaN if not reached in the band)
  tune::ModelMargins model;        // implemented loop (M-method speed) around plant_model
  tune::ModelMargins design;       // loop_analysis.hpp: the config's model, state feedback
  std::size_t samples = 0;         // ticks recorded, all experiments
  int averages = 0;                // multisine periods / Welch segments averaged (the points' experiment)
  double min_coherence = 0.0;      // over the points
  bool observer_enabled = false;   // the model leaves the speed observer out
};

using FreqResponseProgress = std::function<void(const std::string&)>;

// Sets excite.* and capture.* for the experiment and restores them after
// (also on failure). The node must be enabled and holding (a refusal says
// so). Throws std::invalid_argument for bad options, RequestError /
// std::runtime_error when the node refuses or the recording is missing.
FreqResponseResult run_freq_response(NodeClient& client, hal::Axis axis, const FreqResponseOptions& options,
                                     const FreqResponseProgress& progress = {});

// The recorded experiments: the plant's open-loop multisine (loop plant
// only) and the closed-loop one.
struct FreqResponseRecords {
  std::optional<tune::LoopRecord> plant;
  tune::LoopRecord loop;
};

// The estimation alone, from recorded experiments (the same steps as
// run_freq_response after the uploads).
FreqResponseResult estimate_freq_response(const FreqResponseRecords& records, hal::Axis axis,
                                          const FreqResponseOptions& options, const fw::AxisConfig& config);

}  // namespace tnv::can_host
