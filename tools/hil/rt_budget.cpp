#include "tools/hil/rt_budget.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>

#include "drivers/storage/stepped_storage_worker.hpp"
#include "emulator/scenario_file.hpp"
#include "firmware/can/can_id.hpp"
#include "firmware/can/can_node.hpp"
#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/param_table.hpp"
#include "firmware/can/request_tag.hpp"

namespace tnv::hil {

// A named namespace, not an anonymous one: its alias and using-directive
// must not reach the other files of a unity batch.
namespace rt_budget_detail {

namespace can = fw::can;
using namespace can::fields;

constexpr std::uint8_t kBudgetNode = 1;
constexpr std::uint8_t kBudgetHost = 1;  // the bench host's id in every request tag

// The bench's wire: what the host sent waits for the node, what the node
// sent is read back by the session after every service().
class BudgetCanPort final : public hal::CanPort {
 public:
  // Room for a whole service()'s frames: the port's own cost stays out of the measured calls.
  BudgetCanPort() { from_node.reserve(4 * can::kMaxTxPerService); }
  hal::HalStatus try_send(const hal::CanFrame& frame) noexcept override {
    from_node.push_back(frame);
    return hal::HalStatus::ok;
  }
  bool try_receive(hal::CanFrame& frame) noexcept override {
    if (to_node_count == 0) return false;
    frame = to_node[to_node_head];
    to_node_head = (to_node_head + 1) % to_node.size();
    --to_node_count;
    return true;
  }
  // The session sends one request per cycle: a small ring, no allocation.
  bool push_request(const hal::CanFrame& frame) {
    if (to_node_count == to_node.size()) return false;
    to_node[(to_node_head + to_node_count) % to_node.size()] = frame;
    ++to_node_count;
    return true;
  }
  std::array<hal::CanFrame, 16> to_node{};
  std::size_t to_node_head = 0;
  std::size_t to_node_count = 0;
  std::vector<hal::CanFrame> from_node;
};

class BudgetStorage final : public hal::ParamStorage {
 public:
  hal::HalStatus write(std::span<const std::uint8_t> image) noexcept override {
    bytes.assign(image.begin(), image.end());
    return hal::HalStatus::ok;
  }
  hal::HalStatus read(std::span<std::uint8_t> out, std::size_t& size) noexcept override {
    if (bytes.empty()) return hal::HalStatus::not_present;
    if (out.size() < bytes.size()) return hal::HalStatus::bad_address;
    std::copy(bytes.begin(), bytes.end(), out.begin());
    size = bytes.size();
    return hal::HalStatus::ok;
  }
  std::vector<std::uint8_t> bytes;
};

hal::CanFrame budget_command(can::CommandCode code, std::uint32_t axis = 0, std::uint32_t arg = 0) {
  hal::CanFrame f = can::make_frame(kCommandMsg, kBudgetNode);
  can::write_raw(f, kCommandCode, static_cast<std::uint32_t>(code));
  can::write_raw(f, kCommandAxis, axis);
  can::write_raw(f, kCommandArg, arg);
  return f;
}

hal::CanFrame budget_param(can::ParamOp op, std::uint16_t id = 0, std::uint32_t raw = 0) {
  hal::CanFrame f = can::make_frame(kParamRequestMsg, kBudgetNode);
  can::write_raw(f, kParamOp, static_cast<std::uint32_t>(op));
  can::write_raw(f, kParamId, id);
  can::write_raw(f, kParamValue, raw);
  return f;
}

hal::CanFrame budget_capture(can::CaptureOp op, std::uint32_t frames = 0) {  // frames: u8 on the wire
  hal::CanFrame f = can::make_frame(kCaptureControlMsg, kBudgetNode);
  can::write_raw(f, kCaptureOp, static_cast<std::uint32_t>(op));
  can::write_raw(f, kCaptureFrames, frames);
  can::write_raw(f, kCaptureOffset, 0);
  return f;
}

hal::CanFrame budget_excite() {
  hal::CanFrame f = can::make_frame(kExciteMsg, kBudgetNode);
  can::write_raw(f, kExciteAxis, 0);
  can::write_raw(f, kExciteKind, 0);  // step
  can::write(f, kExciteDuration, 0.05);
  can::write(f, kExciteLevel, 2.0);
  return f;
}

hal::CanFrame budget_bore(can::BoreOp op, std::uint32_t part = 0, double top_mm = 0.0, double bottom_mm = 0.0) {
  hal::CanFrame f = can::make_frame(kBoreGaugeMsg, kBudgetNode);
  can::write_raw(f, kBoreOp, static_cast<std::uint32_t>(op));
  can::write_raw(f, kBorePart, part);
  can::write(f, kBoreTop, top_mm);
  can::write(f, kBoreBottom, bottom_mm);
  return f;
}

hal::CanFrame budget_shaper(fw::ShaperType type, double freq_hz) {
  hal::CanFrame f = can::make_frame(kShaperMsg, kBudgetNode);
  can::write_raw(f, kShaperAxis, 0);
  can::write_raw(f, kShaperType, static_cast<std::uint32_t>(type));
  can::write(f, kShaperZeta, 0.05);
  can::write(f, kShaperFreq, freq_hz);
  return f;
}

// Per kind, every call: its host CPU time and its modelled board time, ns.
class BudgetCallLog {
 public:
  struct Sample {
    std::int64_t cpu_ns = 0;
    std::int64_t board_ns = 0;
  };
  void add(const std::string& kind, Sample sample, std::uint64_t refused = 0) {
    auto it = index_.find(kind);
    if (it == index_.end()) {
      it = index_.emplace(kind, samples_.size()).first;
      names_.push_back(kind);
      samples_.emplace_back();
      refused_.push_back(0);
    }
    samples_[it->second].push_back(sample);
    refused_[it->second] += refused;
    all_.push_back(sample);
  }
  void fill(RtBudgetResult& out) const {
    out.overall = row("overall", all_);
    for (std::size_t i = 0; i < names_.size(); ++i) {
      out.kinds.push_back(row(names_[i], samples_[i]));
      out.kinds.back().refused = refused_[i];
      out.overall.refused += refused_[i];
    }
  }

 private:
  // Largest and 99.9th percentile (nearest rank), us.
  static void spread(std::vector<std::int64_t> ns, double& max_us, double& p999_us) {
    std::sort(ns.begin(), ns.end());
    const auto rank = static_cast<std::size_t>(std::ceil(0.999 * static_cast<double>(ns.size())));
    max_us = static_cast<double>(ns.back()) * 1e-3;
    p999_us = static_cast<double>(ns[std::max<std::size_t>(rank, 1) - 1]) * 1e-3;
  }
  static RtBudgetRow row(const std::string& kind, const std::vector<Sample>& samples) {
    RtBudgetRow r;
    r.kind = kind;
    r.calls = samples.size();
    if (samples.empty()) return r;
    std::vector<std::int64_t> cpu;
    std::vector<std::int64_t> board;
    for (const Sample& s : samples) {
      cpu.push_back(s.cpu_ns);
      board.push_back(s.board_ns);
    }
    spread(std::move(cpu), r.max_call_us, r.p999_call_us);
    spread(std::move(board), r.max_board_us, r.p999_board_us);
    return r;
  }

  std::map<std::string, std::size_t> index_;
  std::vector<std::string> names_;
  std::vector<std::vector<Sample>> samples_;
  std::vector<Sample> all_;
  std::vector<std::uint64_t> refused_;
};

class BudgetSession {
 public:
  BudgetSession(std::unique_ptr<HilRig> rig, const can::NodeSettings& settings)
      : rig_(std::move(rig)),
        node_(std::make_unique<can::CanNode>(rig_->task, port_, storage_, settings, false, nullptr, &worker_)) {}

  // One loop cycle: tick, then service() with `request` (if any) waiting.
  void cycle(const hal::CanFrame* request, const char* kind) {
    rig_->tick();
    log_.add("tick", last_call());
    if (request != nullptr) {
      if (port_.push_request(*request)) ++result_.requests;
    }
    const bool storage_before = node_->storage_in_flight();
    const bool design_before = node_->design_in_flight();
    rig_->charged_call([this]() noexcept { node_->service(); });
    const std::uint64_t refused_before = result_.refused;
    const bool uploading = read_answers();
    std::string filed = request != nullptr ? kind
                        : storage_before && !node_->storage_in_flight() ? "storage_reply"
                        : design_before && !node_->design_in_flight()   ? "shaper_reply"
                        : uploading                                      ? "capture_upload"
                                                                         : "service_idle";
    log_.add(filed, last_call(), result_.refused - refused_before);
    // The non-real-time side: a posted save, load or shaper design runs now, outside the charged time.
    if (worker_.run_pending()) ++result_.worker_jobs;
  }
  // Every request goes out as host 1 with its own sequence in the tag (byte 0).
  void request(const hal::CanFrame& frame, const char* kind, int idle_cycles = 3) {
    hal::CanFrame tagged = frame;
    tagged.data[0] = can::make_tag(kBudgetHost, sequence_++);
    cycle(&tagged, kind);
    for (int k = 0; k < idle_cycles; ++k) cycle(nullptr, "");
  }
  // Idle cycles until the node holds again at rest (an excitation ended) or max.
  void run_until_holding(int max_cycles) {
    for (int k = 0; k < max_cycles && (rig_->task.state() != fw::MotionState::holding || rig_->task.exciting()); ++k)
      cycle(nullptr, "");
  }
  void run_until_quiet(int max_cycles) {
    for (int k = 0; k < max_cycles && (uploading_ || node_->storage_in_flight() || node_->design_in_flight()); ++k)
      cycle(nullptr, "");
  }
  std::uint32_t wire_value(const char* name) const {
    const can::ParamDef* p = can::find_param(name);
    return p == nullptr ? 0 : can::to_wire(*p, p->get(node_->settings()));
  }
  std::uint16_t id_of(const char* name) const {
    const can::ParamDef* p = can::find_param(name);
    return p == nullptr ? 0 : p->id;
  }

  void round() {
    for (const char* name : {"x.sliding.eta_mm_s", "y.pid.kp", "capture.channels", "supervisor.max_missed_ticks"})
      request(budget_param(can::ParamOp::get, id_of(name)), "param_get", 0);
    // Live parameters at the values they hold (the servo keeps holding the same way).
    request(budget_param(can::ParamOp::set, id_of("x.sliding.eta_mm_s"), wire_value("x.sliding.eta_mm_s")),
            "param_set");
    for (const char* name : {"x.sliding.eta_mm_s", "x.sliding.phi_mm_s", "y.sliding.eta_mm_s", "y.sliding.phi_mm_s"})
      request(budget_param(can::ParamOp::stage, id_of(name), wire_value(name)), "param_stage", 0);
    request(budget_param(can::ParamOp::commit), "param_commit");
    request(budget_param(can::ParamOp::stage, id_of("y.pid.kp"), wire_value("y.pid.kp")), "param_stage", 0);
    request(budget_param(can::ParamOp::discard), "param_discard");
    request(budget_command(can::CommandCode::save_params), "save_params");
    run_until_quiet(20);
    request(budget_command(can::CommandCode::load_params), "load_params");
    run_until_quiet(20);
    request(budget_command(can::CommandCode::restore_defaults), "restore_defaults");
    request(budget_command(can::CommandCode::select_controller, 255, 2), "select_controller");
    // A spec the node has not designed before, every round (the heaviest types included):
    // the design runs on the worker and the request is answered when it is done.
    const fw::ShaperType type = fw::kShaperTypes[rounds_ % std::size(fw::kShaperTypes)];
    request(budget_shaper(type, 20.0 + 0.37 * static_cast<double>(rounds_ % 100)), "shaper");
    run_until_quiet(20);
    ++rounds_;
    // Identification: a capture armed for the motion records the excitation, then goes up.
    request(budget_capture(can::CaptureOp::arm), "capture_arm");
    request(budget_excite(), "excite");
    run_until_holding(2000);
    request(budget_capture(can::CaptureOp::status), "capture_status");
    request(budget_capture(can::CaptureOp::upload, 255), "capture_upload");
    run_until_quiet(200);
    request(budget_capture(can::CaptureOp::abort), "capture_abort");
    // Boring on the board (restore_defaults switched the planner off): four parts a round, gauged
    // in band, then out of band three times in a row, so the variance perturbation resets P.
    const can::ParamDef& bore = *can::find_param("bore.enable");
    request(budget_param(can::ParamOp::set, bore.id, can::to_wire(bore, 1.0)), "param_set");
    request(budget_bore(can::BoreOp::query), "bore_query");
    constexpr double kReadings[4][2] = {{0.0485, 0.1689}, {0.0102, -0.0213}, {0.21, 0.32}, {0.19, 0.012}};
    for (const auto& reading : kReadings) {
      ++bore_parts_;
      request(budget_bore(can::BoreOp::record, bore_parts_, reading[0], reading[1]),
              bore_parts_ == 1 ? "bore_record_startup" : "bore_record");
    }
  }

  RtBudgetResult finish() {
    log_.fill(result_);
    const fw::TickCounters& c = rig_->task.counters();
    result_.ticks = c.ticks;
    result_.missed_ticks = c.missed_ticks;
    result_.late_ticks = c.late_ticks;
    result_.charged = rig_->charged();
    result_.held = rig_->task.state() == fw::MotionState::holding && !rig_->task.fault().active();
    return result_;
  }

  HilRig& rig() { return *rig_; }

 private:
  BudgetCallLog::Sample last_call() const {
    return {rig_->charged().last_call_cpu_ns, rig_->charged().last_call_ns};
  }
  // Reads what the node sent; true while CAPTURE_DATA frames are going out.
  bool read_answers() {
    bool data = false;
    for (const hal::CanFrame& f : port_.from_node) {
      const auto id = static_cast<can::MessageId>(can::message_of(f.id));
      count_answer(id, f);
      if (id == can::MessageId::capture_data) {
        ++result_.upload_frames;
        data = true;
      }
    }
    port_.from_node.clear();
    uploading_ = data;
    return data;
  }
  void count_answer(can::MessageId id, const hal::CanFrame& f) {
    std::uint32_t result = 0;
    if (id == can::MessageId::command_ack) result = can::read_raw(f, kAckResult);
    else if (id == can::MessageId::param_reply) result = can::read_raw(f, kReplyResult);
    else if (id == can::MessageId::capture_status) result = can::read_raw(f, kStatusResult);
    else if (id == can::MessageId::bore_infeed) result = can::read_raw(f, kBoreResult);
    else return;
    ++result_.replies;
    if (result != static_cast<std::uint32_t>(can::ErrorCode::ok)) ++result_.refused;
  }

  std::unique_ptr<HilRig> rig_;
  BudgetCanPort port_;
  BudgetStorage storage_;
  drivers::SteppedStorageWorker worker_;
  std::unique_ptr<can::CanNode> node_;
  std::uint8_t sequence_ = 0;
  std::uint32_t rounds_ = 0;
  std::uint32_t bore_parts_ = 0;  // parts the bench has gauged (BORE_GAUGE.part of the next is one more)
  BudgetCallLog log_;
  RtBudgetResult result_;
  bool uploading_ = false;
};

}  // namespace rt_budget_detail

RtBudgetResult run_rt_budget(const RtBudgetOptions& options) {
  using namespace rt_budget_detail;
  RtBudgetResult failed;
  emu::ScenarioResult found = emu::resolve_scenario(options.scenario);
  if (!found.scenario) {
    failed.error = found.error.empty() ? "no scenario " + options.scenario : found.error;
    return failed;
  }
  if (options.rounds < 1) {
    failed.error = "rounds must be >= 1";
    return failed;
  }
  std::string error;
  std::unique_ptr<HilRig> rig =
      HilRig::create(*found.scenario, fw::default_firmware_config(), fw::ControllerKind::rdvsc, error);
  if (!rig) {
    failed.error = error;
    return failed;
  }
  rig->charging.measure_cpu_time = true;
  rig->home();
  can::NodeSettings settings = can::default_node_settings();
  settings.firmware = rig->task.config();
  settings.can.node_id = kBudgetNode;
  // Every telemetry message on, at 10 ms (heartbeat 100 ms): the session's background traffic.
  settings.telemetry = {100, 10, 10, 10, 10, 10, 10};
  BudgetSession session(std::move(rig), settings);
  session.request(budget_command(can::CommandCode::take_ownership), "take_ownership");
  session.request(budget_command(can::CommandCode::enable), "enable");
  session.run_until_holding(100);
  if (session.rig().task.state() != fw::MotionState::holding) {
    failed.error = "the servo did not hold after enable";
    return failed;
  }
  for (int r = 0; r < options.rounds; ++r) session.round();
  return session.finish();
}

}  // namespace tnv::hil
