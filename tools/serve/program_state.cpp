#include "tools/serve/program_state.hpp"

#include "firmware/can/program_tracker.hpp"

namespace tnv::serve {

bool ProgramState::begin(const nlohmann::json& summary) {
  const std::lock_guard lock(mutex_);
  if (phase_ == "starting" || phase_ == "running") return false;
  interrupt_ = false;
  estop_ = false;
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
          {"message", message_}, {"program", summary_}, {"interrupting", interrupt_.load()}};
}

}  // namespace tnv::serve
