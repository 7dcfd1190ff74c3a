#include "tools/can/freq_response_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "firmware/can/node_settings.hpp"
#include "firmware/can/param_table.hpp"
#include "firmware/io/dac_code.hpp"
#include "tools/can/capture_run.hpp"
#include "tools/can/capture_table.hpp"
#include "tools/can/freq_response_defaults.hpp"
#include "tools/tune/freq_response_smoothing.hpp"
#include "tools/tune/freq_response_spectra.hpp"

namespace tnv::can_host {

namespace {

constexpr double kFreqTickS = 1e-3;
constexpr std::uint32_t kFreqChannels = 4;  // pos, command, dac, excite of the axis
constexpr double kFreqSettleS = 0.2;        // EXCITE's fixed settle (ExcitationSpec's default)
constexpr double kFreqReturnSpeedMmS = 10.0;  // the move back after a carrier

const char* freq_axis_name(hal::Axis axis) { return hal::axis_label(axis); }

const can::ParamDef& freq_param(const std::string& name) {
  const can::ParamDef* p = can::find_param(name.c_str());
  if (p == nullptr) throw std::logic_error("no parameter " + name);
  return *p;
}

const char* freq_controller_name(fw::ControllerKind k) {
  switch (k) {
    case fw::ControllerKind::pid: return "pid";
    case fw::ControllerKind::dvsc: return "dvsc";
    case fw::ControllerKind::rdvsc: return "rdvsc";
  }
  return "?";
}

// What the experiment changes, as it was.
struct FreqSaved {
  std::vector<std::pair<const can::ParamDef*, double>> values;
};

FreqSaved freq_save(NodeClient& client, const std::vector<std::string>& names) {
  FreqSaved s;
  for (const std::string& n : names) s.values.emplace_back(&freq_param(n), client.get(freq_param(n)));
  return s;
}

void freq_restore(NodeClient& client, const FreqSaved& s) {
  for (const auto& [p, v] : s.values) client.stage(*p, v);
  client.commit();
}

// The axis' controller, model and observer switch as the node has them.
fw::AxisConfig freq_axis_config(NodeClient& client, hal::Axis axis) {
  can::NodeSettings settings = can::cached_default_node_settings();
  const std::string prefix = std::string(freq_axis_name(axis)) + ".";
  for (const can::ParamDef& p : can::param_table()) {
    const std::string name = p.name;
    if (name.rfind(prefix, 0) != 0 || p.set == nullptr) continue;
    const std::string rest = name.substr(prefix.size());
    const bool wanted = rest == "controller" || rest.rfind("model.", 0) == 0 || rest.rfind("sliding.", 0) == 0 ||
                        rest.rfind("pid.", 0) == 0 || rest == "observer.enable" || rest == "hw.count_mm";
    if (wanted) p.set(settings, client.get(p));
  }
  return settings.firmware.axis[hal::index(axis)];
}

std::vector<double> freq_log_spaced(double f0, double f1, std::uint32_t n) {
  std::vector<double> out;
  for (std::uint32_t i = 0; i < n; ++i)
    out.push_back(n == 1 ? f0 : f0 * std::pow(f1 / f0, static_cast<double>(i) / static_cast<double>(n - 1)));
  return out;
}

// One experiment: kind, band, tones, level.
struct FreqExperiment {
  fw::ExcitationKind kind = fw::ExcitationKind::multisine;
  double f_min_hz = 1.0;
  double f_max_hz = 100.0;
  std::uint32_t tones = 40;
  double level_mm_s = 1.0;
  double carrier_mm_s = 0.0;  // closed loop only
};

FreqExperiment plant_experiment(const FreqResponseOptions& o) {
  return {fw::ExcitationKind::multisine_open, o.f_min_hz, o.f_max_hz, o.tones, o.plant_level_mm_s};
}

FreqExperiment loop_experiment(const FreqResponseOptions& o) {
  return {o.kind, o.loop_f_min_hz, o.loop_f_max_hz, o.loop_tones.value(), o.loop_level_mm_s.value(),
          o.carrier_mm_s.value()};
}

fw::ExcitationSpec freq_spec_of(const FreqExperiment& e, double duration_s) {
  fw::ExcitationSpec spec;
  spec.kind = e.kind;
  spec.level_mm_s = e.level_mm_s;
  spec.duration_s = duration_s;
  spec.f_min_hz = e.f_min_hz;
  spec.f_max_hz = e.f_max_hz;
  spec.tones = e.kind == fw::ExcitationKind::sweep ? 1 : e.tones;
  spec.carrier_mm_s = e.carrier_mm_s;
  return spec;
}

std::string check_experiment(const FreqExperiment& e, const FreqResponseOptions& o, const char* which) {
  if (const fw::ParamCheck c = fw::validate(freq_spec_of(e, o.duration_s.value())); !c.ok)
    return std::string(which) + " " + c.field + ": " + c.reason;
  if (e.kind != fw::ExcitationKind::sweep) {
    const std::int64_t period = fw::multisine_period_ticks(e.f_min_hz, kFreqTickS);
    const auto periods = static_cast<std::int64_t>(std::floor(o.duration_s.value() / kFreqTickS + 1e-6)) / period;
    if (o.skip_periods < 0 || periods < o.skip_periods + 1)
      return "skip_periods: must be >= 0 and leave at least one of the record's periods";
  } else if (e.tones < 2) {
    return std::string(which) + " tones: a sweep is read at >= 2 frequencies";
  }
  return "";
}

// The averaged spectra of one recorded experiment at its tones.
std::vector<tune::SpectraPoint> experiment_spectra(const tune::LoopRecord& record, const FreqExperiment& e,
                                                   const FreqResponseOptions& o) {
  if (e.kind == fw::ExcitationKind::sweep) {
    tune::LoopRecord detrended = record;
    if (e.carrier_mm_s != 0.0) tune::remove_linear_trend(detrended.position_mm);
    const auto total = static_cast<std::int64_t>(record.position_mm.size());
    const std::int64_t segment = std::min<std::int64_t>(std::llround(4.0 / (e.f_min_hz * kFreqTickS)), total / 2);
    return tune::welch_spectra(detrended, freq_log_spaced(e.f_min_hz, e.f_max_hz, e.tones), segment);
  }
  const fw::MultisineTones tones = fw::multisine_tones(e.f_min_hz, e.f_max_hz, e.tones, kFreqTickS);
  if (tones.count == 0) throw std::invalid_argument("tones: do not fit the band");
  // Only the drive phase: whole periods (the settle after it is no multisine).
  const std::int64_t drive =
      (static_cast<std::int64_t>(std::floor(o.duration_s.value() / kFreqTickS + 1e-6)) / tones.period_ticks) *
      tones.period_ticks;
  tune::LoopRecord drive_only = record;
  const auto keep = static_cast<std::size_t>(
      std::min<std::int64_t>(drive, static_cast<std::int64_t>(record.position_mm.size())));
  for (std::vector<double>* v :
       {&drive_only.excitation_mm_s, &drive_only.applied_mm_s, &drive_only.controller_mm_s, &drive_only.position_mm})
    v->resize(keep);
  // On a carrier the position ramps: its straight line is the carrier's, not the excitation's.
  if (e.carrier_mm_s != 0.0) tune::remove_linear_trend(drive_only.position_mm);
  const std::vector<std::int32_t> harmonics(tones.harmonic.begin(), tones.harmonic.begin() + tones.count);
  return tune::multisine_spectra(drive_only, tones.period_ticks, harmonics, o.skip_periods);
}

}  // namespace

namespace {

std::string check_resolved(const FreqResponseOptions& o) {
  if (o.smooth_half_window < 0 || o.smooth_half_window > 10) return "smooth_half_window: must be 0 .. 10 tones";
  if (o.kind != fw::ExcitationKind::sweep && o.kind != fw::ExcitationKind::multisine)
    return "kind: the closed-loop experiment is a sweep or a multisine";
  if (const std::string e = check_experiment(loop_experiment(o), o, "closed-loop experiment"); !e.empty()) return e;
  if (o.loop == tune::LoopKind::plant)
    if (const std::string e = check_experiment(plant_experiment(o), o, "plant experiment"); !e.empty()) return e;
  const double room_s = static_cast<double>(can::kCaptureCapacityWords / kFreqChannels) * kFreqTickS;
  if (o.duration_s.value() + kFreqSettleS + 0.05 > room_s) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "duration_s: the capture holds %.1f s of 4 channels at 1 kHz (with the %.1f s settle)",
                  room_s, kFreqSettleS);
    return buf;
  }
  return "";
}

}  // namespace

std::string check_options(const FreqResponseOptions& o) {
  // Every controller's defaults for what is unset (they differ in level and duration).
  const fw::FirmwareConfig defaults = fw::default_firmware_config();
  for (const fw::AxisConfig& axis : defaults.axis)
    for (const fw::ControllerKind kind : {fw::ControllerKind::pid, fw::ControllerKind::rdvsc}) {
      fw::AxisConfig config = axis;
      config.controller = kind;
      if (const std::string e = check_resolved(resolved_options(o, config)); !e.empty()) return e;
    }
  return "";
}

FreqResponseResult estimate_freq_response(const FreqResponseRecords& records, hal::Axis axis,
                                          const FreqResponseOptions& given, const fw::AxisConfig& config) {
  const FreqResponseOptions o = resolved_options(given, config);
  FreqResponseResult r;
  r.options = o;
  r.axis = axis;
  r.loop = o.loop;
  r.kind = o.kind;
  r.controller = freq_controller_name(config.controller);
  r.observer_enabled = config.observer.enabled;
  r.samples = records.loop.position_mm.size() + (records.plant ? records.plant->position_mm.size() : 0);

  const std::vector<tune::SpectraPoint> loop_spectra = experiment_spectra(records.loop, loop_experiment(o), o);
  const std::vector<tune::ResponsePoint> open =
      tune::smoothed_response(tune::loop_response(loop_spectra, tune::LoopKind::open), o.smooth_half_window);
  r.margins = tune::margins_from_points(open);
  r.bandwidth_hz = tune::bandwidth_hz(
      tune::smoothed_response(tune::loop_response(loop_spectra, tune::LoopKind::closed), o.smooth_half_window));

  std::vector<tune::SpectraPoint> point_spectra = loop_spectra;
  if (o.loop == tune::LoopKind::plant) {
    if (!records.plant) throw std::invalid_argument("frequency response: loop plant needs the plant experiment's record");
    point_spectra = experiment_spectra(*records.plant, plant_experiment(o), o);
    r.kind = fw::ExcitationKind::multisine_open;
  }
  r.averages = point_spectra.empty() ? 0 : point_spectra.front().averages;
  const std::vector<tune::ResponsePoint> chosen = tune::loop_response(point_spectra, o.loop);

  tune::LoopModel implemented;
  implemented.plant = o.plant_model.value_or(config.model);
  implemented.controller = tune::active_linear_controller(config);
  implemented.measured_speed = true;
  tune::LoopModel design = implemented;
  design.plant = config.model;
  design.measured_speed = false;
  r.model = tune::model_margins(implemented);
  r.design = tune::model_margins(design);
  r.plant_model = o.plant_model ? "exact 1 ms ZOH of the emulated table" : "the node's configured model";

  r.min_coherence = chosen.empty() ? 0.0 : 1.0;
  for (const tune::ResponsePoint& p : chosen) {
    r.points.push_back({p.freq_hz, p.response, p.coherence, tune::model_response(implemented, o.loop, p.freq_hz)});
    r.min_coherence = std::min(r.min_coherence, p.coherence);
  }
  return r;
}

namespace {

// Band, tones and capture set, one EXCITE, wait, upload: the record.
// A carrier goes the other way when the soft limits leave no room ahead
// (carrier_used_mm_s: as it went), and the table is moved back after.
tune::LoopRecord record_experiment(NodeClient& client, hal::Axis axis, const fw::DacScale& dac, can::ChannelMask mask,
                                   const FreqExperiment& e, double duration_s, const FreqResponseProgress& progress,
                                   double& carrier_used_mm_s) {
  const std::string a = freq_axis_name(axis);
  // One commit: the node checks the band as a whole.
  client.stage(freq_param("excite.f_min_hz"), e.f_min_hz);
  client.stage(freq_param("excite.f_max_hz"), e.f_max_hz);
  client.stage(freq_param("excite.tones"), freq_spec_of(e, duration_s).tones);
  client.stage(freq_param("excite.carrier_mm_s"), e.carrier_mm_s);
  stage_channel_mask(client, mask);
  client.stage(freq_param("capture.trigger"), static_cast<double>(can::CaptureTrigger::motion));
  client.stage(freq_param("capture.decimation"), 1.0);
  client.commit();
  if (progress) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s: %s %.3g..%.3g Hz, level %g mm/s, carrier %.6g mm/s, %g s", a.c_str(),
                  e.kind == fw::ExcitationKind::sweep ? "sweep" : e.kind == fw::ExcitationKind::multisine ? "multisine"
                                                                                                         : "open-loop multisine",
                  e.f_min_hz, e.f_max_hz, e.level_mm_s, e.carrier_mm_s, duration_s);
    progress(buf);
  }
  client.capture(can::CaptureOp::arm);
  double carrier_mm_s = e.carrier_mm_s;
  try {
    try {
      client.excite(static_cast<std::uint8_t>(hal::index(axis)), static_cast<std::uint8_t>(e.kind), e.level_mm_s,
                    duration_s);
    } catch (const RequestError& err) {
      // A carrier whose travel would leave the soft limits: the other way.
      if (err.kind() != RequestError::Kind::refused || err.code() != can::ErrorCode::out_of_range ||
          carrier_mm_s == 0.0)
        throw;
      carrier_mm_s = -carrier_mm_s;
      client.set(freq_param("excite.carrier_mm_s"), carrier_mm_s);
      client.excite(static_cast<std::uint8_t>(hal::index(axis)), static_cast<std::uint8_t>(e.kind), e.level_mm_s,
                    duration_s);
    }
  } catch (const RequestError& err) {
    if (err.kind() != RequestError::Kind::refused) throw;
    client.capture(can::CaptureOp::abort);
    std::string message = err.what();
    if (err.code() == can::ErrorCode::busy || err.code() == can::ErrorCode::faulted)
      message.append(": a frequency response needs the node enabled and holding at rest (tnvctl enable; no "
                     "motion, no fault)");
    if (err.code() == can::ErrorCode::out_of_range && carrier_mm_s != 0.0) {
      char buf[160];
      std::snprintf(buf, sizeof buf, ": the carrier's travel (%.1f mm) leaves the soft limits either way",
                    std::fabs(carrier_mm_s) * duration_s);
      message.append(buf);
    }
    throw RequestError(RequestError::Kind::refused, message, err.code());
  }
  carrier_used_mm_s = carrier_mm_s;
  const CaptureStatus status =
      client.wait_capture_done(Micros{static_cast<long long>((duration_s + kFreqSettleS + 2.0) * 1e6)}, Micros{50'000});
  if (carrier_mm_s != 0.0) {
    // Back to where the table stood: the reference moved carrier x drive phase, exactly.
    fw::ExcitationSpec spec = freq_spec_of(e, duration_s);
    spec.carrier_mm_s = carrier_mm_s;
    fw::ExcitationGenerator drive;
    drive.start(spec);
    const double travel_mm = carrier_mm_s * static_cast<double>(drive.drive_ticks()) * kFreqTickS;
    client.wait_at_rest(Micros{2'000'000});
    client.move(static_cast<std::uint8_t>(hal::index(axis)), -travel_mm, kFreqReturnSpeedMmS);
    client.wait_at_rest(Micros{static_cast<long long>((std::fabs(travel_mm) / kFreqReturnSpeedMmS + 5.0) * 1e6)});
  }
  const std::vector<std::uint8_t> image = client.upload(status);
  std::string error;
  const std::optional<CaptureTable> table = decode_capture(image, mask, status.samples, status.decimation, error);
  if (!table) throw std::runtime_error("frequency response: " + error);
  const std::vector<double>* pos = table->column("pos_" + a);
  const std::vector<double>* command = table->column("command_" + a);
  const std::vector<double>* code = table->column("dac_" + a);
  const std::vector<double>* excite = table->column("excite_" + a);
  if (pos == nullptr || command == nullptr || code == nullptr || excite == nullptr || status.decimation != 1)
    throw std::runtime_error("frequency response: the capture lacks the axis' channels at every tick");
  tune::LoopRecord record;
  record.period_s = kFreqTickS;
  record.position_mm = *pos;
  record.excitation_mm_s = *excite;
  for (std::size_t k = 0; k < pos->size(); ++k) {
    record.applied_mm_s.push_back(fw::dac_code_to_speed_mm_s(static_cast<std::uint16_t>((*code)[k]), dac));
    record.controller_mm_s.push_back((*command)[k] - (*excite)[k]);
  }
  return record;
}

}  // namespace

FreqResponseResult run_freq_response(NodeClient& client, hal::Axis axis, const FreqResponseOptions& given,
                                     const FreqResponseProgress& progress) {
  if (const std::string e = check_options(given); !e.empty()) throw std::invalid_argument(e);
  const std::string a = freq_axis_name(axis);
  fw::DacScale dac;
  dac.full_scale_mm_s = client.get(freq_param(a + ".hw.dac_full_scale_mm_s"));
  const fw::AxisConfig config = freq_axis_config(client, axis);
  FreqResponseOptions o = resolved_options(given, config);
  if (const std::string e = check_resolved(o); !e.empty()) throw std::invalid_argument(e);

  if (const can::CaptureState st = client.capture(can::CaptureOp::status).state;
      st == can::CaptureState::recording || st == can::CaptureState::armed)
    client.capture(can::CaptureOp::abort);  // capture.* cannot change while armed
  const FreqSaved before =
      freq_save(client, {"capture.channels", "capture.channels_high", "capture.trigger", "capture.decimation", "excite.f_min_hz",
                         "excite.f_max_hz", "excite.tones", "excite.carrier_mm_s"});
  std::string error;
  const std::optional<can::ChannelMask> mask =
      parse_channel_list("pos_" + a + ",command_" + a + ",dac_" + a + ",excite_" + a, error);
  if (!mask) throw std::logic_error(error);

  FreqResponseRecords records;
  try {
    if (o.loop == tune::LoopKind::plant) {
      double no_carrier = 0.0;
      records.plant =
          record_experiment(client, axis, dac, *mask, plant_experiment(o), *o.duration_s, progress, no_carrier);
      client.pump(Micros{300'000});  // at rest before the next experiment
    }
    double carrier_used_mm_s = 0.0;
    records.loop =
        record_experiment(client, axis, dac, *mask, loop_experiment(o), *o.duration_s, progress, carrier_used_mm_s);
    o.carrier_mm_s = carrier_used_mm_s;
  } catch (...) {
    try {
      freq_restore(client, before);
    } catch (const std::exception&) {
      // The first failure is the one to report.
    }
    throw;
  }
  freq_restore(client, before);
  return estimate_freq_response(records, axis, o, config);
}

}  // namespace tnv::can_host
