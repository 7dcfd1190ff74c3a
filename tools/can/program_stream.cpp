#include "tools/can/program_stream.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <memory>

#include "firmware/can/node_fields.hpp"

namespace tnv::can_host {

namespace {

using can::MessageId;
using fw::can::ProgramState;

constexpr Micros kPumpSlice{5'000};
constexpr Micros kStopWait{10'000'000};  // a controlled stop on the path takes well under a second
constexpr Micros kStatusRefresh{1'000'000};

bool over(ProgramState s) { return s == ProgramState::done || s == ProgramState::aborted; }

}  // namespace

class Streamer {
  struct InFlight {
    std::size_t index;
    std::uint8_t tag;
    Micros sent_at;
  };

 public:
  Streamer(NodeClient& client, const WireProgram& program, const StreamOptions& options)
      : client_(client), program_(program), o_(options) {}
  ~Streamer() {
    if (listening_) client_.set_listener({});
  }
  Streamer(const Streamer&) = delete;
  Streamer& operator=(const Streamer&) = delete;

  StreamResult run() {
    if (!ended_) {
      listen();
      stream();
    }
    unlisten();
    return r_;
  }

  // Sends what is not yet sent; the last element is a probe move: waits for its PROBE_RESULT (with
  // PROBE_RESULT_Z and PROBE_REST). nullopt: the run ended (run() says how).
  std::optional<ProbeResult> run_to_probe() {
    if (ended_) return std::nullopt;
    listen();
    start();
    const std::optional<std::uint8_t> seen = probe_ ? std::optional<std::uint8_t>(probe_->count) : std::nullopt;
    if (!send_all()) return std::nullopt;
    const double ratio = o_.feed_override ? std::max(*o_.feed_override, 0.05) : 1.0;
    const Micros limit{static_cast<long long>((o_.expected_s * 1.5 / ratio + 10.0) * 1e6)};
    const Micros deadline = client_.bus().now() + limit;
    Micros last_poll = client_.bus().now();
    const auto decided = [&] { return probe_ && (!seen || probe_->count != *seen); };
    while (!decided()) {
      // The result is sent once: ask again now and then (PROGRAM_STATUS brings it again) in case it was lost.
      if (client_.bus().now() - last_poll >= kStatusRefresh) {
        last_poll = client_.bus().now();
        client_.send_raw(command_request(client_.node(), client_.next_tag(), can::CommandCode::program_status, 0, 0, 0.0));
      }
      handle_pause();
      handle_hold();
      if (!failure_ && over(status_.state)) failure_ = "the node stopped the program before the probe's result";
      if (failure_) return stop(StreamResult::End::failed, *failure_), std::nullopt;
      if (o_.interrupted && o_.interrupted()) return stop(StreamResult::End::interrupted, "interrupted"), std::nullopt;
      if (client_.bus().now() > deadline + paused_time() + held_time())
        return stop(StreamResult::End::failed, "no probe result within " + std::to_string(limit.count() / 1'000'000) +
                                                   " s"),
               std::nullopt;
      client_.pump_until([&] { return decided() || failure_.has_value() || over(status_.state); }, Micros{50'000});
    }
    return probe_;
  }

  // The program's time so far (the wait for a probe's result is 1.5 x this + 10 s).
  void set_expected_s(double s) { o_.expected_s = s; }

  // The run ends failed here (the program cannot go on): a controlled stop if anything was sent.
  StreamResult abandon(const std::string& why) {
    if (!ended_ && started_ && over(status_.state)) {  // the node stopped it already (a probe's error)
      ended_ = true;
      r_.end = StreamResult::End::failed;
      r_.message = why;
      finish();
    } else if (!ended_) {
      listen();
      stop(StreamResult::End::failed, why);
    }
    unlisten();
    return r_;
  }

 private:
  void listen() {
    if (listening_) return;
    listening_ = true;
    client_.set_listener([this](const hal::CanFrame& f, MessageId id) { on_frame(f, id); });
  }
  void unlisten() {
    if (!listening_) return;
    listening_ = false;
    client_.set_listener({});
  }

  void start() {
    if (started_) return;
    started_ = true;
    const ProgramStatus before = client_.program_status();
    if (fw::can::active(before.state))
      throw RequestError(RequestError::Kind::refused, "node " + std::to_string(client_.node()) +
                                                          " is already running a program (" +
                                                          fw::can::to_string(before.state) + ")");
    capacity_ = before.free_slots;
    r_.queue_capacity = capacity_;
    first_sent_ = client_.bus().now();
    last_poll_ = first_sent_;
  }

  void stream() {
    start();
    if (!send_all()) return;
    if (!filled_) mark_filled(client_.bus().now());
    try {
      client_.command(can::CommandCode::end_program);
    } catch (const RequestError& e) {
      return stop(StreamResult::End::failed, e.what());
    }
    wait_end();
  }

  // Sends every element of the program and waits for their answers; false: the run ended (stopped).
  bool send_all() {
    const std::size_t window = std::clamp<std::size_t>(o_.window, 1, 15);
    Micros& last_poll = last_poll_;
    while (next_ < program_.elements.size() || !flight_.empty()) {
      if (failure_) return stop(StreamResult::End::failed, *failure_), false;
      if (o_.interrupted && o_.interrupted()) return stop(StreamResult::End::interrupted, "interrupted"), false;
      if (acked_ > 0 && o_.feed_override && !override_sent_) set_override();
      handle_pause();
      handle_hold();
      while (next_ < program_.elements.size() && flight_.size() < window && room() > 0) send_next();
      const Micros now = client_.bus().now();
      if (!flight_.empty() && now - flight_.front().sent_at > client_.options().timeout) {
        failure_ = element_text(flight_.front().index) + ": no answer within " +
                   std::to_string(client_.options().timeout.count() / 1000) + " ms";
        continue;
      }
      if (flight_.empty() && room() == 0) {
        if (!filled_) mark_filled(now);
        if (now - last_poll >= o_.poll_period) {
          last_poll = now;
          // Answered by an ack the streamer ignores and a fresh PROGRAM_STATUS.
          client_.send_raw(command_request(client_.node(), client_.next_tag(), can::CommandCode::program_status, 0, 0, 0.0));
        }
      }
      news_ = false;
      client_.pump_until([this] { return news_ || failure_.has_value(); }, kPumpSlice);
    }
    return true;
  }

  // Time the node has rested at pauses so far (the one it rests at now included).
  Micros paused_time() const {
    return paused_total_ + (pause_ ? client_.bus().now() - pause_since_ : Micros{0});
  }

  // A pause the node reports: told once, then cycle_start when the caller says go.
  void handle_pause() {
    if (!pause_ || resume_sent_ || failure_) return;
    if (!o_.resume) {
      failure_ = "the program paused at " + pause_text(*pause_) + " and this run does not continue pauses";
      return;
    }
    if (!o_.resume(*pause_, client_.bus().now() - pause_since_)) return;
    resume_sent_ = true;
    try {
      client_.command(can::CommandCode::cycle_start);
    } catch (const RequestError& e) {
      failure_ = "cycle start at " + pause_text(*pause_) + " refused: " + e.what();
    }
  }

  // Time the feed has been held so far (the hold on now included).
  Micros held_time() const { return held_total_ + (held_ ? client_.bus().now() - held_since_ : Micros{0}); }

  // The caller's feed hold switch, sent when it changes (once the node has the program).
  void handle_hold() {
    if (!o_.feed_hold || acked_ == 0 || failure_) return;
    const bool want = o_.feed_hold();
    if (want == held_) return;
    try {
      client_.command(want ? can::CommandCode::feed_hold : can::CommandCode::feed_resume);
    } catch (const RequestError& e) {
      failure_ = std::string(want ? "feed hold" : "feed resume") + " refused: " + e.what();
      return;
    }
    const Micros now = client_.bus().now();
    if (want) held_since_ = now;
    else held_total_ += now - held_since_;
    held_ = want;
    r_.held_s = static_cast<double>(held_time().count()) * 1e-6;
  }

  void mark_filled(Micros now) {
    filled_ = true;
    const double s = static_cast<double>((now - first_sent_).count()) * 1e-6;
    if (s > 0.0) r_.fill_elements_per_s = static_cast<double>(acked_) / s;
  }

  void set_override() {
    override_sent_ = true;
    const double percent = std::round(std::clamp(*o_.feed_override, 0.0, 1.5) * 100.0);
    try {
      client_.command(can::CommandCode::feed_override, 0, static_cast<std::uint8_t>(percent));
    } catch (const RequestError& e) {
      failure_ = e.what();
    }
  }

  // Lower bound of the node's free queue slots, minus what is on its way (see the header).
  std::size_t room() const {
    const long in_flight = static_cast<long>(flight_.size());
    long free = last_ack_free_ >= 0 ? last_ack_free_ - in_flight : 0;
    const long done = running_ > 0 ? static_cast<long>(running_) - 1 : 0;
    free = std::max(free, static_cast<long>(capacity_) - (static_cast<long>(acked_) - done) - in_flight);
    return free > 0 ? static_cast<std::size_t>(free) : 0;
  }

  void send_next() {
    WireElement e = program_.elements[next_];
    const std::uint8_t tag = client_.next_tag();
    if (o_.before_send) o_.before_send(next_);
    e.frames.head.data[0] = tag;
    client_.send_raw(e.frames.head);
    if (e.frames.has_z) {
      e.frames.z.data[0] = tag;
      client_.send_raw(e.frames.z);
    }
    if (e.frames.has_tail) {
      e.frames.tail.data[0] = tag;
      client_.send_raw(e.frames.tail);
    }
    flight_.push_back({next_, tag, client_.bus().now()});
    r_.max_in_flight = std::max(r_.max_in_flight, flight_.size());
    r_.sent = ++next_;
  }

  void on_frame(const hal::CanFrame& f, MessageId id) {
    if (id == MessageId::command_ack) on_ack(read_command_ack(f));
    if (id == MessageId::program_status) on_status(read_program_status(f));
    if (id == MessageId::program_tool) on_tool(read_program_tool(f));
    if (id == MessageId::probe_result || id == MessageId::probe_result_z || id == MessageId::probe_rest) on_probe(f, id);
    if (id == MessageId::heartbeat) {
      r_.final_heartbeat = read_heartbeat(f);
      if (r_.final_heartbeat->state == fw::MotionState::faulted && !failure_ && acked_ > 0 && !over(status_.state))
        failure_ = std::string("the node faulted: ") + fw::to_string(r_.final_heartbeat->fault);
    }
    if (o_.on_frame) o_.on_frame(f, id);
  }

  void on_ack(const CommandAck& a) {
    const auto segment = static_cast<std::uint8_t>(MessageId::segment);
    const auto tail = static_cast<std::uint8_t>(MessageId::segment_tail);
    const auto z = static_cast<std::uint8_t>(MessageId::segment_z);
    const auto plane = static_cast<std::uint8_t>(MessageId::segment_plane);
    if (a.request != segment && a.request != tail && a.request != z && a.request != plane) return;
    news_ = true;
    if (flight_.empty() || a.tag != flight_.front().tag) {
      for (const InFlight& f : flight_)
        if (f.tag == a.tag && !failure_) failure_ = element_text(f.index) + " answered before the elements sent ahead of it";
      return;  // a stale answer (an element of an aborted run)
    }
    const InFlight f = flight_.front();
    flight_.pop_front();
    last_ack_free_ = a.code;
    r_.min_free_slots = std::min<int>(r_.min_free_slots, a.code);
    if (a.result != can::ErrorCode::ok) {
      if (!failure_) failure_ = refusal_text(f.index, a);
      return;
    }
    r_.acknowledged = ++acked_;
  }

  // The three frames of one probe result, in the order the node sends them.
  void on_probe(const hal::CanFrame& f, MessageId id) {
    news_ = true;
    namespace fields = can::fields;
    const auto count = static_cast<std::uint8_t>(f.data[0]);
    if (id == MessageId::probe_result) {
      probe_part_ = ProbeResult{};
      probe_part_->count = count;
      probe_part_->outcome = static_cast<fw::motion::ProbeOutcome>(can::read(f, fields::kProbeOutcome));
      probe_part_->trip_mm[0] = can::read(f, fields::kProbeTripX);
      probe_part_->trip_mm[1] = can::read(f, fields::kProbeTripY);
      probe_has_z_ = false;
    } else if (!probe_part_ || probe_part_->count != count) {
      return;  // the rest of a result whose first frame was not seen
    } else if (id == MessageId::probe_result_z) {
      probe_part_->trip_mm[fw::can::kProgramZ] = can::read(f, fields::kProbeTripZ);
      probe_part_->rest_mm[fw::can::kProgramZ] = can::read(f, fields::kProbeRestZ);
      probe_has_z_ = true;
    } else if (probe_has_z_) {
      probe_part_->rest_mm[0] = can::read(f, fields::kProbeRestX);
      probe_part_->rest_mm[1] = can::read(f, fields::kProbeRestY);
      probe_ = *probe_part_;
      probe_part_.reset();
    }
  }

  void on_status(const ProgramStatus& s) {
    news_ = true;
    if (acked_ == 0) return;  // from before this program
    status_ = s;
    r_.final_status = s;
    r_.underruns = s.underruns;
    if (fw::can::active(s.state)) running_ = std::max(running_, s.element);
    track_pause(s);
    report(s);
  }

  // PROGRAM_TOOL comes right after its PROGRAM_STATUS: a new tool is reported with that status.
  void on_tool(const ProgramTool& t) {
    const bool news = r_.final_tool != t;
    r_.final_tool = t;
    if (news && acked_ > 0) report(status_);
  }

  void report(const ProgramStatus& s) {
    if (!o_.progress) return;
    StreamProgress p;
    p.tool = r_.final_tool;
    p.sent = next_;
    p.acknowledged = acked_;
    p.total = program_.elements.size();
    p.running = fw::can::active(s.state) ? s.element : static_cast<std::uint32_t>(acked_);
    p.line = p.running > 0 && p.running <= p.total ? program_.elements[p.running - 1].line : 0;
    p.fraction = s.state == ProgramState::done ? 1.0 : length_fraction(program_, p.running > 0 ? p.running - 1 : 0);
    p.underruns = s.underruns;
    p.state = s.state;
    o_.progress(p);
  }

  void track_pause(const ProgramStatus& s) {
    const bool paused = s.state == ProgramState::paused;
    // A feed hold while paused shows holding on the pause's element: still the same pause, not a new one after it.
    const bool held_at_pause = pause_ && s.state == ProgramState::holding && s.element == pause_->element;
    if (pause_ && !held_at_pause && (!paused || s.element != pause_->element)) {  // left it (continued, or stopped)
      paused_total_ += client_.bus().now() - pause_since_;
      r_.paused_s = static_cast<double>(paused_total_.count()) * 1e-6;
      pause_.reset();
      resume_sent_ = false;
    }
    if (!paused || pause_) return;
    StreamPause p;
    p.element = s.element;
    if (s.element >= 1 && s.element <= program_.elements.size()) {
      const WireElement& e = program_.elements[s.element - 1];
      p.line = e.line;
      p.why = e.pause;
    }
    pause_ = p;
    pause_since_ = client_.bus().now();
    r_.pauses.push_back(p);
    if (o_.on_pause) o_.on_pause(p);
  }

  std::string element_text(std::size_t index) const {
    return "element " + std::to_string(index + 1) + " (line " + std::to_string(program_.elements[index].line) + ")";
  }

  std::string refusal_text(std::size_t index, const CommandAck& a) const {
    std::string out = element_text(index) + " refused by node " + std::to_string(client_.node()) + ": ";
    out += can::to_string(a.result);
    const can::MessageDef* m = can::find_message(a.request);
    if (m != nullptr && a.detail != 0 && a.detail < m->fields.size())
      out.append(" (").append(message_label(static_cast<MessageId>(a.request))).append(".").append(m->fields[a.detail].name).append(")");
    out.append(", state ").append(fw::to_string(a.state));
    if (a.result == can::ErrorCode::not_owner)
      out += a.owner == 0 ? ", no host owns the node" : ", host " + std::to_string(a.owner) + " owns the node";
    return out;
  }

  // Waits for PROGRAM_STATUS done / aborted after end_program.
  void wait_end() {
    const double ratio = o_.feed_override ? std::max(*o_.feed_override, 0.05) : 1.0;
    const Micros limit{static_cast<long long>((o_.expected_s * 1.5 / ratio + 10.0) * 1e6)};
    const Micros deadline = client_.bus().now() + limit;
    Micros last_poll = client_.bus().now();
    while (!over(status_.state)) {
      // The change to done is sent once: ask again now and then in case that frame was lost.
      if (client_.bus().now() - last_poll >= kStatusRefresh) {
        last_poll = client_.bus().now();
        client_.send_raw(command_request(client_.node(), client_.next_tag(), can::CommandCode::program_status, 0, 0, 0.0));
      }
      handle_pause();
      handle_hold();
      if (failure_) return stop(StreamResult::End::failed, *failure_);
      if (o_.interrupted && o_.interrupted()) return stop(StreamResult::End::interrupted, "interrupted");
      if (client_.bus().now() > deadline + paused_time() + held_time())
        return stop(StreamResult::End::failed, "the program did not end within " +
                                                   std::to_string(limit.count() / 1'000'000) + " s");
      client_.pump_until([this] { return over(status_.state) || failure_.has_value(); }, Micros{50'000});
    }
    ended_ = true;
    finish();
    if (status_.state == ProgramState::aborted) {
      r_.end = StreamResult::End::failed;
      r_.message = "the node stopped the program before its end";
      if (r_.final_heartbeat && r_.final_heartbeat->fault != fw::FaultReason::none)
        r_.message.append(" (fault ").append(fw::to_string(r_.final_heartbeat->fault)).append(")");
      return;
    }
    r_.end = StreamResult::End::done;
  }

  // A controlled stop on the path (abort_program), then the wait until it rests.
  void stop(StreamResult::End end, const std::string& why) {
    ended_ = true;
    r_.end = end;
    r_.message = why;
    if (acked_ == 0 && flight_.empty()) return finish();
    try {
      client_.command(can::CommandCode::abort_program);
    } catch (const RequestError& e) {
      r_.message.append("; the abort was refused: ").append(e.what());
    }
    // Answers of elements still on their way come first; once one was accepted, wait for the stop.
    client_.pump_until([this] { return (acked_ == 0 && flight_.empty()) || over(status_.state); }, kStopWait);
    finish();
  }

  void finish() {
    r_.run_s = static_cast<double>((client_.bus().now() - first_sent_).count()) * 1e-6;
    r_.underruns = status_.underruns;
    r_.held_s = static_cast<double>(held_time().count()) * 1e-6;
  }

  NodeClient& client_;
  const WireProgram& program_;
  StreamOptions o_;
  StreamResult r_{};
  std::deque<InFlight> flight_;
  std::size_t next_ = 0;
  std::size_t acked_ = 0;
  std::size_t capacity_ = 0;
  long last_ack_free_ = -1;
  std::uint32_t running_ = 0;
  ProgramStatus status_{};
  std::optional<std::string> failure_;
  Micros first_sent_{0};
  bool news_ = false;
  bool listening_ = false;
  bool started_ = false;
  bool ended_ = false;  // stopped or ended: nothing more is sent
  Micros last_poll_{0};
  std::optional<ProbeResult> probe_part_;  // PROBE_RESULT seen, its other frames awaited
  bool probe_has_z_ = false;
  std::optional<ProbeResult> probe_;  // the last complete result
  bool filled_ = false;
  bool override_sent_ = false;
  std::optional<StreamPause> pause_;  // the pause the node rests at
  bool resume_sent_ = false;
  bool held_ = false;  // feed_hold sent and not yet resumed
  Micros held_since_{0};
  Micros held_total_{0};
  Micros pause_since_{0};
  Micros paused_total_{0};
};

std::string pause_text(const StreamPause& pause) {
  std::string out = "line " + std::to_string(pause.line) + ": ";
  if (!pause.why) return out + "pause (element " + std::to_string(pause.element) + ")";
  return out + gcode::to_string(*pause.why);
}

StreamResult stream_program(NodeClient& client, const WireProgram& program, const StreamOptions& options) {
  return Streamer(client, program, options).run();
}

ProgramStreamer::ProgramStreamer(NodeClient& client, const WireProgram& program, const StreamOptions& options)
    : impl_(std::make_unique<Streamer>(client, program, options)) {}
ProgramStreamer::~ProgramStreamer() = default;
std::optional<ProbeResult> ProgramStreamer::run_to_probe(double expected_s) {
  impl_->set_expected_s(expected_s);
  return impl_->run_to_probe();
}
StreamResult ProgramStreamer::finish(double expected_s) {
  impl_->set_expected_s(expected_s);
  return impl_->run();
}
StreamResult ProgramStreamer::abandon(const std::string& why) { return impl_->abandon(why); }

}  // namespace tnv::can_host
