#include "tools/can_emu/bus_stress.hpp"

#include <algorithm>
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include <unistd.h>

#include "firmware/can/node_fields.hpp"
#include "firmware/can/param_table.hpp"
#include "firmware/can/request_tag.hpp"
#include "tools/can/node_messages.hpp"
#include "tools/can_emu/emulated_bus.hpp"

namespace tnv::can_host {

namespace {

namespace can = fw::can;
using can::MessageId;

constexpr int kMaxHosts = 4;
constexpr std::size_t kFloodBacklog = 24;  // host frames kept queued at saturation (tests/can_host/bus_flood_test.cpp)
constexpr Micros kReplyTimeout{250'000};
constexpr Micros kRetakePause{5'000};
constexpr Micros kAfterEstop{500'000};
constexpr std::int64_t kMaxTicks = 60'000;

// Parameters the hosts stage, each at its current value: a commit changes
// nothing the circle depends on, but its applied count shows whose set it was.
constexpr std::array<const char*, 6> kStagedParams{"motion.circle_ramp_s", "motion.circle_dwell_s", "motion.move_ramp_s",
                                                   "motion.move_dwell_s",  "tlm.position_ms",       "tlm.heartbeat_ms"};

enum class Step : std::uint8_t { stage, take, commit, release, get, status };

struct Expected {
  MessageId reply = MessageId::param_reply;
  std::uint8_t request = 0;  // COMMAND_ACK.request
  std::uint8_t code = 0;     // COMMAND_ACK.code
  std::optional<std::uint16_t> param;  // PARAM_REPLY.param when ok
};

struct Host {
  std::uint8_t id = 0;
  std::vector<std::pair<Step, std::uint16_t>> script;  // step, parameter id (stage/get)
  std::size_t next = 0;
  std::uint8_t sequence = 0;
  bool waiting = false;
  std::uint8_t tag = 0;
  Expected expected{};
  Micros sent_at{0};
  Micros resume_at{0};
  std::size_t staged = 0;  // distinct parameters this host staged and the node kept
  bool done() const { return !waiting && next >= script.size(); }
};

hal::CanFrame request_for(std::uint8_t node, Host& h, const can::NodeSettings& live, Expected& e) {
  const auto [step, param] = h.script[h.next];
  h.sequence = static_cast<std::uint8_t>((h.sequence + 1) & 0x0Fu);
  h.tag = can::make_tag(h.id, h.sequence);
  e = Expected{};
  switch (step) {
    case Step::stage: {
      const can::ParamDef* p = can::find_param(param);
      e.param = param;
      return param_request(node, h.tag, can::ParamOp::stage, param, can::to_wire(*p, p->get(live)));
    }
    case Step::get: e.param = param; return param_request(node, h.tag, can::ParamOp::get, param, 0);
    case Step::commit: return param_request(node, h.tag, can::ParamOp::commit, 0, 0);
    case Step::take:
    case Step::release: {
      const can::CommandCode code =
          step == Step::take ? can::CommandCode::take_ownership : can::CommandCode::release_ownership;
      e.reply = MessageId::command_ack;
      e.request = static_cast<std::uint8_t>(MessageId::command);
      e.code = static_cast<std::uint8_t>(code);
      return command_request(node, h.tag, code, 0, 0, 0.0);
    }
    case Step::status:
      e.reply = MessageId::capture_status;
      return capture_request(node, h.tag, can::CaptureOp::status, 0, 0);
  }
  return {};
}

// The reply's tag, for the three kinds of reply.
std::optional<std::uint8_t> tag_of(const hal::CanFrame& f, MessageId id) {
  switch (id) {
    case MessageId::command_ack: return read_command_ack(f).tag;
    case MessageId::param_reply: return read_param_reply(f).tag;
    case MessageId::capture_status: return read_capture_status(f).tag;
    default: return std::nullopt;
  }
}

bool answers(const hal::CanFrame& f, MessageId id, const Expected& e) {
  if (id != e.reply) return false;
  if (id == MessageId::command_ack) {
    const CommandAck a = read_command_ack(f);
    return a.request == e.request && a.code == e.code;
  }
  if (id == MessageId::param_reply && e.param) {
    const ParamReply r = read_param_reply(f);
    return r.result != can::ErrorCode::ok || r.param == *e.param;
  }
  return true;
}

double ms(Micros t) { return static_cast<double>(t.count()) / 1000.0; }

}  // namespace

std::string validate(const BusStressOptions& o) {
  if (o.flood_id > 0x7FFu) return "--flood-id must be an 11-bit identifier (0 .. 0x7ff)";
  if (!(o.load >= 0.0 && o.load <= 1.0)) return "--load must be between 0 and 1";
  if (o.hosts < 1 || o.hosts > kMaxHosts) return "--hosts must be 1 .. 4";
  if (o.rounds < 0 || o.rounds > 10'000) return "rounds must be 0 .. 10000";
  return "";
}

BusStressResult run_bus_stress(const BusStressOptions& o) {
  BusStressResult out;
  if (out.error = validate(o); !out.error.empty()) return out;
  EmulatedNodeOptions eo;
  eo.scenario = o.scenario;
  std::string file = "tnv_bus_stress_";
  file.append(std::to_string(::getpid()));
  eo.storage_path = (std::filesystem::temp_directory_path() / file).string();  // never saved to
  std::unique_ptr<EmulatedBus> bus = EmulatedBus::create(eo, out.error);
  if (!bus) return out;
  const std::uint8_t node = bus->node_id();
  const fw::TickTask& task = bus->rig().task;

  // Host 1 takes command ownership and starts the circle, then gives ownership up (the circle runs on).
  const emu::Scenario& sc = bus->scenario();
  bus->send(command_request(node, can::make_tag(1, 14), can::CommandCode::take_ownership, 0, 0, 0.0));
  bus->send(circle_request(node, can::make_tag(1, 15), sc.circle.radius_mm, sc.circle.feed_mm_s));
  bus->send(command_request(node, can::make_tag(1, 0), can::CommandCode::release_ownership, 0, 0, 0.0));
  for (int k = 0; k < 20; ++k) {
    bus->step();
    while (bus->receive(Micros{0})) {
    }
  }
  if (task.state() != fw::MotionState::dwell && task.state() != fw::MotionState::moving) {
    out.error = "the circle did not start on the emulated node";
    return out;
  }

  std::vector<Host> hosts(static_cast<std::size_t>(o.hosts));
  for (std::size_t i = 0; i < hosts.size(); ++i) {
    Host& h = hosts[i];
    h.id = static_cast<std::uint8_t>(i + 1);
    for (std::size_t k = 0; k <= i + 1 && k < kStagedParams.size(); ++k)
      h.script.emplace_back(Step::stage, can::find_param(kStagedParams[(i + k) % kStagedParams.size()])->id);
    h.script.emplace_back(Step::take, 0);
    h.script.emplace_back(Step::commit, 0);
    h.script.emplace_back(Step::release, 0);
    const auto params = can::param_table();
    for (int r = 0; r < o.rounds; ++r) {
      h.script.emplace_back(Step::get, params[(static_cast<std::size_t>(r) * 7 + i) % params.size()].id);
      h.script.emplace_back(Step::status, 0);
    }
  }

  const std::uint64_t bits_per_flood_frame = VirtualCanBus::frame_bits(hal::CanFrame{o.flood_id, false, 8, {}});
  const double bits_per_tick = static_cast<double>(bus->wire().bitrate_bit_s()) / 1000.0;
  double flood_credit_bits = 0.0;
  const Micros start = bus->now();
  const std::uint64_t busy_at_start = bus->wire().counters().busy_bits;
  std::optional<Micros> last_heartbeat = start;  // a run without any heartbeat reports its whole length
  std::optional<Micros> estop_at;
  bool started = false;
  const can::NodeCounters node_at_start = bus->node().counters();
  for (std::int64_t k = 0; k < kMaxTicks; ++k) {
    // The flood: credit at the offered load, never more queued than the saturation backlog.
    flood_credit_bits = std::min(flood_credit_bits + o.load * bits_per_tick,
                                 static_cast<double>(kFloodBacklog * bits_per_flood_frame));
    while (flood_credit_bits >= static_cast<double>(bits_per_flood_frame) &&
           bus->wire().pending(BusSide::host) < kFloodBacklog) {
      hal::CanFrame f{o.flood_id, false, 8, {}};
      f.data = {0xA5, 0x5A, static_cast<std::uint8_t>(k), 0, 0, 0, 0, 0};
      bus->send(f);
      flood_credit_bits -= static_cast<double>(bits_per_flood_frame);
      ++out.flood_frames;
    }
    // The hosts: one request outstanding each.
    const Micros now = bus->now();
    for (Host& h : hosts) {
      if (h.waiting && now - h.sent_at > kReplyTimeout) {  // lost: the host gives up on it and goes on
        h.waiting = false;
        ++h.next;
      }
      if (h.waiting || h.next >= h.script.size() || now < h.resume_at) continue;
      bus->send(request_for(node, h, bus->node().settings(), h.expected));
      h.waiting = true;
      h.sent_at = now;
      ++out.requests;
    }
    // The ESTOP, into the flood, once the circle is well under way (or over).
    const std::int64_t motion_tick = task.last_record().motion_tick;
    started = started || motion_tick >= 0;
    const bool circle_over = started && motion_tick < 0;
    if (!estop_at && (motion_tick >= o.estop_motion_tick || circle_over)) {
      bus->send(estop_request(node));
      estop_at = now;
    }
    bus->step();
    while (const std::optional<hal::CanFrame> f = bus->receive(Micros{0})) {
      const can::MessageDef* m = can::classify(*f);
      if (m == nullptr || m->direction != can::Direction::from_node || can::node_of(f->id) != node) continue;
      const auto id = static_cast<MessageId>(m->id);
      const Micros t = bus->now();
      if (id == MessageId::heartbeat) {
        if (last_heartbeat) out.heartbeat_max_gap_ms = std::max(out.heartbeat_max_gap_ms, ms(t - *last_heartbeat));
        last_heartbeat = t;
        continue;
      }
      if (id == MessageId::fault_event) {
        if (estop_at && out.fault_event_delay_ms < 0.0) out.fault_event_delay_ms = ms(t - *estop_at);
        continue;
      }
      const std::optional<std::uint8_t> tag = tag_of(*f, id);
      if (!tag) continue;  // telemetry, capture data
      const std::uint8_t host = can::host_of_tag(*tag);
      Host* h = host >= 1 && host <= hosts.size() ? &hosts[host - 1] : nullptr;
      if (h == nullptr || !h->waiting || h->tag != *tag) {
        ++out.replies_stale;
        continue;
      }
      if (!answers(*f, id, h->expected)) {
        ++out.replies_misattributed;  // right tag, another request's answer
        continue;
      }
      ++out.replies_received;
      h->waiting = false;
      const Step step = h->script[h->next].first;
      if (step == Step::take && read_command_ack(*f).result == can::ErrorCode::not_owner) {
        h->resume_at = t + kRetakePause;  // another host commits: ask again
        continue;
      }
      if (step == Step::stage && read_param_reply(*f).result == can::ErrorCode::ok) ++h->staged;
      if (step == Step::commit) {
        ++out.commits;
        const ParamReply r = read_param_reply(*f);
        if (r.result != can::ErrorCode::ok || r.param != h->staged) ++out.staged_sets_crossed;
      }
      ++h->next;
    }
    const bool hosts_done = std::all_of(hosts.begin(), hosts.end(), [](const Host& h) { return h.done(); });
    if (hosts_done && estop_at && bus->now() - *estop_at >= kAfterEstop) break;
  }
  const Micros elapsed = bus->now() - start;
  if (last_heartbeat) out.heartbeat_max_gap_ms = std::max(out.heartbeat_max_gap_ms, ms(bus->now() - *last_heartbeat));
  out.bus_load = static_cast<double>(bus->wire().counters().busy_bits - busy_at_start) /
                 (static_cast<double>(elapsed.count()) * 1e-6 * static_cast<double>(bus->wire().bitrate_bit_s()));
  out.missed_ticks = task.counters().missed_ticks;
  out.late_ticks = task.counters().late_ticks;
  out.telemetry_dropped = bus->node().counters().telemetry_dropped - node_at_start.telemetry_dropped;
  out.node_tx_dropped = bus->node().counters().tx_dropped - node_at_start.tx_dropped;
  out.circle_ran = started;
  std::error_code ignored;
  std::filesystem::remove(eo.storage_path, ignored);
  return out;
}

}  // namespace tnv::can_host
