// NodeParameters: PARAM_REQUEST (get / set / stage / commit / discard),
// applying a whole parameter set, and restore_defaults. stage / commit /
// discard act on the requesting host's own staged set; set and commit need
// command ownership, get and stage do not.
#include "firmware/can/node_parameters.hpp"

#include "firmware/can/command_result.hpp"
#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/param_fallback.hpp"
#include "firmware/can/param_image.hpp"
#include "firmware/can/param_table.hpp"
#include "firmware/can/staged_params.hpp"

namespace tnv::fw::can {

using namespace fields;

NodeParameters::NodeParameters(std::uint8_t node_id, TickTask& task, const HostAccess& access,
                               CommissioningMode& commissioning, NodeTransmit& tx, NodeStorage& storage,
                               ShaperDesignDeferral& design, const NodeCapture& capture,
                               const NodeSettings& settings) noexcept
    : node_id_(node_id),
      task_(task),
      access_(access),
      commissioning_(commissioning),
      tx_(tx),
      storage_(storage),
      design_(design),
      capture_(capture),
      settings_(settings),
      defaults_(cached_default_node_settings()) {
  // The defaults' shaper designs, made here once per process: restore_defaults then copies them.
  (void)cached_default_shaper_designs();
  // The task at rest takes the whole firmware part (controller per axis
  // included); if it refuses, the settings say what the task really runs.
  if (task_.apply_config(settings_.firmware) != CommandStatus::ok) settings_.firmware = task_.config();
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    if (!settings_.shaper[i].enabled) continue;
    const hal::Axis axis = hal::axis_from_index(i);
    shaper_configured_[i] = task_.configure_shaper(axis, settings_.shaper[i].spec) == CommandStatus::ok;
    if (!shaper_configured_[i] || task_.enable_shaper(axis, true) != CommandStatus::ok) settings_.shaper[i].enabled = false;
  }
}

std::size_t NodeParameters::staged_count(std::uint8_t host) const noexcept {
  const StagedParams* s = staged_.find(host);
  return s != nullptr ? s->size() : 0;
}

void NodeParameters::reply(ErrorCode result, std::uint16_t param, std::uint32_t value) noexcept {
  hal::CanFrame frame = make_frame(kParamReplyMsg, node_id_);
  write_raw(frame, kReplyTag, access_.tag());
  write_raw(frame, kReplyResult, static_cast<std::uint32_t>(result));
  write_raw(frame, kReplyParam, param);
  write_raw(frame, kReplyValue, value);
  tx_.answer(frame, result);
}

bool NodeParameters::capture_change_refused(const NodeSettings& next) const noexcept {
  if (!capture_.settings_locked()) return false;
  const CaptureSettings& a = settings_.capture;
  const CaptureSettings& b = next.capture;
  return a.channels != b.channels || a.channels_high != b.channels_high || a.trigger != b.trigger || a.decimation != b.decimation;
}

// The one way a parameter change reaches the task: the whole next set is
// validated, refused busy where it must wait for rest, then applied between
// two ticks (this runs in service()), all of it or none of it. A shaper
// design the node lacks is made on the worker first (ShaperDesignDeferral), so
// no request designs one here.
ErrorCode NodeParameters::apply(const NodeSettings& next, bool idle_touched, bool may_defer) noexcept {
  // A save, load or design in flight works on the set as it was: no change until it is answered.
  if (worker_busy()) return ErrorCode::busy;
  // The live set passed validate(): only what the change touches is checked again.
  if (const SettingsCheck c = validate(next, settings_); !c.ok) {
    blamed_param_ = c.param;
    return ErrorCode::invalid;
  }
  // Safety parameters change only in commissioning mode (docs/safety.md).
  if (!commissioning_.refresh())
    if (const std::uint16_t id = first_safety_change(settings_, next); id != 0) {
      blamed_param_ = id;
      return ErrorCode::commissioning_required;
    }
  if (idle_touched && task_.moving()) return ErrorCode::busy;
  if (capture_change_refused(next)) return ErrorCode::busy;
  // Shapers to configure, and their designs where the node has them.
  std::array<bool, hal::kAxisCount> redesign{};
  std::array<const ShaperDesign*, hal::kAxisCount> ready{};
  std::array<bool, hal::kAxisCount> missing{};
  bool any_missing = false;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const ShaperSettings& now = next.shaper[i];
    redesign[i] = !same_spec(settings_.shaper[i].spec, now.spec) || (now.enabled && !shaper_configured_[i]);
    if (redesign[i]) ready[i] = designs_.find(now.spec);
    missing[i] = redesign[i] && ready[i] == nullptr;
    any_missing = any_missing || missing[i];
  }
  if (any_missing && may_defer && design_.can_defer()) return design_.defer(missing, next);
  // Gains, limits, controller selection: the task checks again and applies whole.
  if (const CommandStatus st = task_.apply_config(next.firmware); st != CommandStatus::ok) return to_error(st);
  // Shapers: validated with the set above, so the designs fit; they apply at the next quiet reference.
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const hal::Axis axis = hal::axis_from_index(i);
    const ShaperSettings& now = next.shaper[i];
    // Without a worker (or a design the load job could not make) the design runs here, as it must.
    if (redesign[i])
      shaper_configured_[i] = (ready[i] != nullptr ? task_.configure_shaper(axis, now.spec, *ready[i])
                                                   : task_.configure_shaper(axis, now.spec)) == CommandStatus::ok;
    if (settings_.shaper[i].enabled != now.enabled) task_.enable_shaper(axis, now.enabled && shaper_configured_[i]);
  }
  if (differing_params(settings_, next, 1) != 0) storage_.changed();
  settings_ = next;
  return ErrorCode::ok;
}

void NodeParameters::handle(const hal::CanFrame& frame) noexcept {
  const auto op_raw = static_cast<std::uint8_t>(read_raw(frame, kParamOp));
  const auto id = static_cast<std::uint16_t>(read_raw(frame, kParamId));
  const std::uint32_t raw = read_raw(frame, kParamValue);
  if (op_raw >= kParamOpCount) {
    reply(ErrorCode::unknown_command, id, 0);
    return;
  }
  const auto op = static_cast<ParamOp>(op_raw);
  const std::uint8_t host = access_.host();
  if ((op == ParamOp::set || op == ParamOp::commit) && !access_.owns()) {
    reply(ErrorCode::not_owner, id, 0);
    return;
  }
  if (op == ParamOp::commit) {
    const StagedParams* mine = staged_.find(host);
    const auto n = static_cast<std::uint16_t>(mine != nullptr ? mine->size() : 0u);
    if (mine == nullptr) {
      reply(ErrorCode::ok, 0, 0);  // nothing staged by this host: nothing applied
      return;
    }
    NodeSettings next = settings_;
    mine->write_into(next);
    bool idle = false;
    for (const StagedParam& s : mine->items()) {
      const ParamDef* p = find_param(s.id);
      idle = idle || (p != nullptr && p->apply == Apply::idle);
    }
    blamed_param_ = 0;
    const ErrorCode e = apply(next, idle);
    if (design_.deferred()) return;  // handled again, and answered, when the designs are made
    if (e == ErrorCode::ok) staged_.clear(host);  // refused: the pending set stays for a fix or a discard
    const bool blamed = e == ErrorCode::invalid || e == ErrorCode::commissioning_required;
    reply(e, n, blamed ? blamed_param_ : 0u);
    return;
  }
  if (op == ParamOp::discard) {
    reply(ErrorCode::ok, static_cast<std::uint16_t>(staged_.clear(host)), 0);
    return;
  }
  const ParamDef* p = find_param(id);
  if (p == nullptr) {
    reply(ErrorCode::unknown_id, id, 0);
    return;
  }
  const std::uint32_t current = to_wire(*p, p->get(settings_));
  if (op == ParamOp::get) {
    reply(ErrorCode::ok, id, current);
    return;
  }
  // set / stage of a safety parameter: authorised before anything else is checked.
  if (const ErrorCode e = commissioning_.check_change(*p, raw, current); e != ErrorCode::ok) {
    reply(e, id, current);
    return;
  }
  // set / stage: the value exactly as it arrived (an f32 stays that float).
  const double value = from_wire(*p, raw);
  if (const ErrorCode e = check_value(*p, value); e != ErrorCode::ok) {
    reply(e, id, current);
    return;
  }
  if (op == ParamOp::stage) {
    StagedParams* mine = staged_.find_or_claim(host);  // nullptr: every set is held by other hosts
    const bool kept = mine != nullptr && mine->put(id, value);
    reply(kept ? ErrorCode::ok : ErrorCode::busy, id, kept ? to_wire(*p, value) : current);
    return;
  }
  NodeSettings next = settings_;
  p->set(next, value);
  const ErrorCode e = apply(next, p->apply == Apply::idle);
  if (design_.deferred()) return;  // handled again, and answered, when the designs are made
  reply(e, id, to_wire(*p, p->get(settings_)));
}

// --- restore_defaults (idle only; save and load: NodeStorage, StorageRequests)

// The papers' defaults, except what describes this machine and this node:
// the encoder count, DAC scale and tick period (commissioning and board facts), the bus
// identity (node id, bit rate), so the node stays reachable and sane, and what the boring
// planner has learned of the process.
// The defaults were computed once, when the first node was built: default_node_settings()
// runs the PID tuning (milliseconds), which must not run in service().
// Outside commissioning mode the safety parameters are kept as well.
ErrorCode NodeParameters::restore_defaults() noexcept {
  if (task_.moving()) return ErrorCode::busy;
  NodeSettings next = defaults_;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    next.firmware.axis[i].count_mm = settings_.firmware.axis[i].count_mm;
    next.firmware.axis[i].dac = settings_.firmware.axis[i].dac;
    next.firmware.axis[i].home_position_mm = settings_.firmware.axis[i].home_position_mm;
  }
  // The board's tick period is the board's fact too (tnv-fw sets it from the board).
  next.firmware.supervisor.tick_period_clocks = settings_.firmware.supervisor.tick_period_clocks;
  next.firmware.supervisor.period_tolerance_clocks = settings_.firmware.supervisor.period_tolerance_clocks;
  next.can.node_id = settings_.can.node_id;
  next.can.bitrate_kbit = settings_.can.bitrate_kbit;
  // What the boring planner learned is no setting: BORE_GAUGE restart clears it.
  next.bore_state = settings_.bore_state;
  if (!commissioning_.refresh()) keep_safety_params(settings_, next);
  return apply(next, true);
}

}  // namespace tnv::fw::can
