#pragma once
// Plant identification over CAN (issue 7): the identification sequence of
// the HIL rig (tools/tune/identification_sequence.hpp), each excitation started by an
// EXCITE and recorded by the node's own capture (trigger motion: first
// tick of the excitation to its last), uploaded, cut into the same
// StepRecord / RampRecord and fitted by identify_from_records(). The same
// code runs on SocketCAN and on the emulated controller.
#include <functional>
#include <string>
#include <vector>

#include "firmware/compensation/excitation.hpp"
#include "firmware/io/dac_code.hpp"
#include "hal/axis.hpp"
#include "tools/can/node_client.hpp"
#include "tools/tune/axis_identification.hpp"

namespace tnv::can_host {

// One excitation's per-tick series, index 0 = its first tick (as the rig
// records them): encoder position and the DAC-quantised command applied.
struct ExcitationSeries {
  std::vector<double> position_mm;
  std::vector<double> command_mm_s;
  std::vector<double> accel_mm_s2;  // tool-side accelerometer, when captured (else empty)
};

// Progress lines ("x: step +10 mm/s"), for stderr.
using IdentifyProgress = std::function<void(const std::string&)>;

// Arms the capture (capture.* must already select pos_<axis>, dac_<axis>
// (and accel_<axis> for the structural mode), trigger motion, decimation 1), sends EXCITE, waits for the recording and
// uploads it. The spec's rate, settle and breakaway must be the EXCITE
// message's fixed ones (ExcitationSpec's defaults): std::invalid_argument
// otherwise. Throws RequestError (a refusal names the state: the node must
// be enabled and holding).
ExcitationSeries run_excitation_over_can(NodeClient& client, hal::Axis axis, const fw::ExcitationSpec& spec,
                                         const fw::DacScale& dac);

// The whole sequence on one axis, then the fit. Sets capture.channels,
// .trigger and .decimation for it and restores them afterwards. Throws
// RequestError / std::runtime_error when the node refuses or a recording
// is missing; a fit that fails comes back with ok = false and its error.
tune::AxisIdentification identify_axis_over_can(NodeClient& client, hal::Axis axis,
                                               const IdentifyProgress& progress = {});

}  // namespace tnv::can_host
