#include "tools/can/can_identify.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "firmware/can/param_table.hpp"
#include "tools/can/capture_run.hpp"
#include "tools/can/capture_table.hpp"
#include "tools/tune/identification_sequence.hpp"

namespace tnv::can_host {

namespace {

constexpr double kIdentifyPeriodS = 1e-3;  // decimation 1: one sample per tick
constexpr Micros kHoldBetween{300'000};    // at rest between excitations, as on the rig

const char* excite_axis_name(hal::Axis axis) { return hal::axis_label(axis); }

const can::ParamDef& identify_param(const std::string& name) {
  const can::ParamDef* p = can::find_param(name.c_str());
  if (p == nullptr) throw std::logic_error("no parameter " + name);
  return *p;
}

// The capture parameters the identification sets, and what was there before
// (raw values; named apart from capture_run.hpp's CaptureSetup for the unity build).
struct CaptureParamValues {
  double channels = 0.0;
  double channels_high = 0.0;
  double trigger = 0.0;
  double decimation = 0.0;
};

CaptureParamValues read_capture_params(NodeClient& client) {
  return {client.get(identify_param("capture.channels")), client.get(identify_param("capture.channels_high")),
          client.get(identify_param("capture.trigger")),
          client.get(identify_param("capture.decimation"))};
}

void write_capture_params(NodeClient& client, const CaptureParamValues& s) {
  client.stage(identify_param("capture.channels"), s.channels);
  client.stage(identify_param("capture.channels_high"), s.channels_high);
  client.stage(identify_param("capture.trigger"), s.trigger);
  client.stage(identify_param("capture.decimation"), s.decimation);
  client.commit();
}

std::string excitation_text(hal::Axis axis, const fw::ExcitationSpec& spec) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s: %s %+g mm/s", excite_axis_name(axis),
                spec.kind == fw::ExcitationKind::step ? "step" : "ramp to", spec.level_mm_s);
  return buf;
}

}  // namespace

ExcitationSeries run_excitation_over_can(NodeClient& client, hal::Axis axis, const fw::ExcitationSpec& spec,
                                         const fw::DacScale& dac) {
  const fw::ExcitationSpec fixed{};
  if (spec.rate_mm_s2 != fixed.rate_mm_s2 || spec.settle_s != fixed.settle_s ||
      spec.breakaway_counts != fixed.breakaway_counts)
    throw std::invalid_argument("EXCITE carries kind, level and duration only: rate, settle and breakaway must be "
                                "the ExcitationSpec defaults");
  const std::string pos_name = std::string("pos_") + excite_axis_name(axis);
  const std::string dac_name = std::string("dac_") + excite_axis_name(axis);
  const auto axis_index = static_cast<std::uint8_t>(hal::index(axis));
  client.capture(can::CaptureOp::arm);
  try {
    client.excite(axis_index, spec.kind == fw::ExcitationKind::step ? 0 : 1, spec.level_mm_s, spec.duration_s);
  } catch (const RequestError& e) {
    if (e.kind() != RequestError::Kind::refused) throw;
    client.capture(can::CaptureOp::abort);
    std::string message = e.what();
    if (e.code() == can::ErrorCode::busy || e.code() == can::ErrorCode::faulted)
      message.append(": identification needs the node enabled and holding at rest (tnvctl enable; no motion, "
                     "no fault)");
    throw RequestError(RequestError::Kind::refused, message, e.code());
  }
  const double longest_s = spec.duration_s + spec.settle_s + 1.0;
  const CaptureStatus status =
      client.wait_capture_done(Micros{static_cast<long long>(longest_s * 1e6)}, Micros{20'000});
  const std::vector<std::uint8_t> image = client.upload(status);
  const can::ChannelMask mask = read_channel_mask(client);
  std::string error;
  const std::optional<CaptureTable> table = decode_capture(image, mask, status.samples, status.decimation, error);
  if (!table) throw std::runtime_error(excitation_text(axis, spec) + ": " + error);
  const std::vector<double>* pos = table->column(pos_name);
  const std::vector<double>* code = table->column(dac_name);
  if (pos == nullptr || code == nullptr || status.decimation != 1)
    throw std::runtime_error(excitation_text(axis, spec) + ": the capture lacks " + pos_name + " / " + dac_name +
                             " at every tick");
  ExcitationSeries out;
  out.position_mm = *pos;
  if (const std::vector<double>* accel = table->column(std::string("accel_") + excite_axis_name(axis))) out.accel_mm_s2 = *accel;
  out.command_mm_s.reserve(code->size());
  for (const double c : *code) out.command_mm_s.push_back(fw::dac_code_to_speed_mm_s(static_cast<std::uint16_t>(c), dac));
  return out;
}

tune::AxisIdentification identify_axis_over_can(NodeClient& client, hal::Axis axis, const IdentifyProgress& progress) {
  const std::string prefix = std::string(excite_axis_name(axis)) + ".";
  fw::DacScale dac;  // the firmware's 12-bit DAC; its full scale from the node
  dac.full_scale_mm_s = client.get(identify_param(prefix + "hw.dac_full_scale_mm_s"));

  if (const can::CaptureState st = client.capture(can::CaptureOp::status).state;
      st == can::CaptureState::recording || st == can::CaptureState::armed)
    client.capture(can::CaptureOp::abort);  // capture.* cannot change while armed
  const CaptureParamValues before = read_capture_params(client);
  std::string error;
  const std::string channels = std::string("pos_") + excite_axis_name(axis) + ",dac_" + excite_axis_name(axis);
  // With the tool-side accelerometer where the protocol has it: the structural mode (tools/tune/mode_fit.hpp).
  std::optional<can::ChannelMask> mask = parse_channel_list(channels + ",accel_" + excite_axis_name(axis), error);
  if (!mask) mask = parse_channel_list(channels, error);
  if (!mask) throw std::logic_error(error);
  write_capture_params(client, {static_cast<double>(can::channel_mask_low(*mask)),
                                static_cast<double>(can::channel_mask_high(*mask)),
                                static_cast<double>(can::CaptureTrigger::motion), 1.0});

  std::vector<tune::StepRecord> steps;
  std::vector<tune::RampRecord> ramps;
  try {
    for (const fw::ExcitationSpec& spec : tune::identification_steps()) {
      if (progress) progress(excitation_text(axis, spec));
      const ExcitationSeries s = run_excitation_over_can(client, axis, spec, dac);
      steps.push_back(tune::step_record_from(spec, s.position_mm, s.command_mm_s));
      steps.back().accel_mm_s2 = s.accel_mm_s2;  // the whole excitation: drive and settle
      client.pump(kHoldBetween);
    }
    for (const fw::ExcitationSpec& spec : tune::identification_ramps()) {
      if (progress) progress(excitation_text(axis, spec));
      const ExcitationSeries s = run_excitation_over_can(client, axis, spec, dac);
      ramps.push_back(tune::ramp_record_from(s.position_mm, s.command_mm_s));
      client.pump(kHoldBetween);
    }
  } catch (...) {
    try {
      write_capture_params(client, before);
    } catch (const std::exception&) {
      // The first failure is the one to report.
    }
    throw;
  }
  write_capture_params(client, before);
  return tune::identify_from_records(axis, steps, ramps, kIdentifyPeriodS);
}

}  // namespace tnv::can_host
