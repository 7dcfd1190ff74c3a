#include "tools/serve/program_state.hpp"

#include "firmware/can/program_tracker.hpp"

namespace tnv::serve {

bool ProgramState::begin(const nlohmann::json& summary) {
  const std::lock_guard lock(mutex_);
  if (phase_ == "starting" || phase_ == "running") return false;
  interrupt_ = false;
  estop_ = false;
  resume_ = false;
  hold_ = false;
  node_state_ = "none";
  pause_ = nullptr;
  spindle_tool_ = nullptr;  // this run's PROGRAM_STATUS brings it again
  phase_ = "starting";
  ++run_;
  summary_ = summary;
  line_ = 0;
  element_ = 0;
  total_ = 0;
  fraction_ = 0.0;
  underruns_ = 0;
  end_.clear();
  message_.clear();
  return true;
}

void ProgramState::streaming() {
  const std::lock_guard lock(mutex_);
  phase_ = "running";
}

void ProgramState::progress(const can_host::StreamProgress& p) {
  const std::lock_guard lock(mutex_);
  total_ = p.total;
  underruns_ = p.underruns;
  node_state_ = fw::can::to_string(p.state);
  if (p.tool)
    spindle_tool_ = {{"known", p.tool->known}, {"tool", p.tool->known ? nlohmann::json(p.tool->tool) : nullptr},
                     {"text", can_host::to_string(*p.tool)}};
  if (p.state != fw::can::ProgramState::paused) pause_ = nullptr;
  // Before the node runs (and after an abort) the stream's progress names the last element accepted,
  // not one that ran: the page shows the line the table is on.
  if (!fw::can::active(p.state) && p.state != fw::can::ProgramState::done) return;
  if (p.line > 0) line_ = p.line;
  element_ = p.running;
  fraction_ = p.fraction;
}

void ProgramState::finish(const std::string& end, const std::string& message) {
  const std::lock_guard lock(mutex_);
  phase_ = "ended";
  pause_ = nullptr;
  end_ = end;
  message_ = message;
}

bool ProgramState::interrupt(bool estop) {
  const std::lock_guard lock(mutex_);
  if (phase_ != "starting" && phase_ != "running") return false;
  if (estop) estop_ = true;  // before the flag the stream looks at
  interrupt_ = true;
  return true;
}

void ProgramState::paused(const can_host::StreamPause& pause) {
  const std::lock_guard lock(mutex_);
  resume_ = false;  // a Resume pressed before this pause is not an answer to it
  pause_ = {{"line", pause.line}, {"text", can_host::pause_text(pause)}, {"reason", nullptr}, {"tool", nullptr}};
  if (pause.why) {
    pause_["reason"] = gcode::to_string(pause.why->reason);
    if (pause.why->reason == gcode::PauseReason::tool_change) pause_["tool"] = pause.why->tool;
  }
  if (pause.line > 0) line_ = pause.line;
}

bool ProgramState::resume() {
  const std::lock_guard lock(mutex_);
  if (phase_ != "running" || pause_.is_null()) return false;
  resume_ = true;
  return true;
}

bool ProgramState::feed_hold(bool on) {
  const std::lock_guard lock(mutex_);
  if (phase_ != "running") return false;
  hold_ = on;
  return true;
}

bool ProgramState::active() const {
  const std::lock_guard lock(mutex_);
  return phase_ == "starting" || phase_ == "running";
}

bool ProgramState::is_streaming() const {
  const std::lock_guard lock(mutex_);
  return phase_ == "running";
}

nlohmann::json ProgramState::json() const {
  const std::lock_guard lock(mutex_);
  return {{"phase", phase_},   {"run", run_},         {"line", line_},           {"element", element_},
          {"total", total_},   {"fraction", fraction_}, {"underruns", underruns_}, {"end", end_},
          {"message", message_}, {"program", summary_}, {"interrupting", interrupt_.load()}, {"pause", pause_},
          {"spindle_tool", spindle_tool_}, {"feed_hold", hold_.load()}, {"node_state", node_state_}};
}

}  // namespace tnv::serve
