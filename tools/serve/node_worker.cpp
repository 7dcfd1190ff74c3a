#include "tools/serve/node_worker.hpp"

#include <chrono>
#include <cstdio>

#include "firmware/can/node_fields.hpp"
#include "hal/axis_choice.hpp"
#include "tools/can/telemetry_json.hpp"
#include "tools/serve/api_error.hpp"

namespace tnv::serve {

namespace {

// Short enough that a queued request starts within a few ms, long enough
// that an idle server does not spin.
constexpr can_host::Micros kReceiveSlice{5'000};

nlohmann::json fault_json(const can_host::FaultEvent& ev) {
  return {{"reason", fw::to_string(ev.reason)},
          {"axis", ev.axis < 0 ? nlohmann::json(nullptr) : nlohmann::json(hal::axis_label_or(ev.axis, "?"))},
          {"value", ev.value},
          {"tick_low", ev.tick_low}};
}

}  // namespace

NodeWorker::NodeWorker(can_host::NodeClient& client, can_host::EmulatedBus* emulated, ScopeRing& ring,
                       std::size_t max_pending_jobs)
    : client_(client), emulated_(emulated), ring_(ring), max_pending_(max_pending_jobs) {
  status_ = {{"heartbeat", nullptr}, {"fault", nullptr}, {"bus_error", ""}};
}

NodeWorker::~NodeWorker() { stop(); }

void NodeWorker::start() {
  started_ = client_.bus().now();
  client_.set_listener(scope_listener());
  if (emulated_ != nullptr) emulated_->set_realtime(true);  // simulated time at wall-clock pace: it looks live
  thread_ = std::thread([this] { loop(); });
}

void NodeWorker::stop() {
  {
    const std::lock_guard lock(mutex_);
    if (stopping_ && !thread_.joinable()) return;
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  client_.set_listener({});
  if (emulated_ != nullptr) emulated_->set_realtime(false);
  const std::lock_guard lock(mutex_);
  for (Pending& p : jobs_)
    p.result.set_exception(std::make_exception_ptr(ApiError(kHttpUnavailable, "the server is stopping")));
  jobs_.clear();
}

can_host::FrameListener NodeWorker::scope_listener() {
  return [this](const hal::CanFrame& f, fw::can::MessageId id) { take_frame(f, id); };
}

nlohmann::json NodeWorker::run(Job job) { return submit(std::move(job)).get(); }

std::future<nlohmann::json> NodeWorker::submit(Job job) {
  ++offered_;
  std::future<nlohmann::json> result;
  {
    const std::lock_guard lock(mutex_);
    if (stopping_) throw ApiError(kHttpUnavailable, "the server is stopping");
    if (jobs_.size() >= max_pending_) {
      std::string message = "the node is busy: ";
      message.append(std::to_string(jobs_.size())).append(" requests are waiting; try again");
      throw ApiError(kHttpUnavailable, message);
    }
    jobs_.push_back(Pending{std::move(job), {}});
    result = jobs_.back().result.get_future();
  }
  wake_.notify_all();
  return result;
}

std::size_t NodeWorker::pending() const {
  const std::lock_guard lock(mutex_);
  return jobs_.size();
}

nlohmann::json NodeWorker::status() const {
  const std::lock_guard lock(mutex_);
  return status_;
}

void NodeWorker::take_frame(const hal::CanFrame& frame, fw::can::MessageId id) {
  view_.take(frame, id);
  // A scope sample per tick of positions: when the last axis' position has come.
  if (static_cast<std::uint8_t>(id) != fw::can::fields::kPositionMsgs.back()->id) return;
  const double t_s = static_cast<double>((client_.bus().now() - started_).count()) * 1e-6;
  ring_.push(scope_sample(view_, t_s));
}

void NodeWorker::refresh_status() {
  nlohmann::json hb = client_.last_heartbeat() ? can_host::heartbeat_json(*client_.last_heartbeat()) : nullptr;
  nlohmann::json fault = client_.last_fault_event() ? fault_json(*client_.last_fault_event()) : nullptr;
  // Display only: the page shows the spindle but cannot start it (docs/tuning-guide.md).
  nlohmann::json spindle = view_.spindle ? can_host::spindle_json(*view_.spindle) : nullptr;
  const std::lock_guard lock(mutex_);
  status_["heartbeat"] = std::move(hb);
  status_["fault"] = std::move(fault);
  status_["spindle"] = std::move(spindle);
}

void NodeWorker::loop() {
  for (;;) {
    std::optional<Pending> next;
    {
      const std::lock_guard lock(mutex_);
      if (stopping_) return;
      if (!jobs_.empty()) {
        next.emplace(std::move(jobs_.front()));
        jobs_.pop_front();
      }
    }
    if (next) {
      try {
        next->result.set_value(next->job(client_));
      } catch (...) {
        next->result.set_exception(std::current_exception());
      }
      client_.set_listener(scope_listener());  // a job that listened itself (a program run) may have left another
      refresh_status();
      continue;
    }
    try {
      client_.pump(kReceiveSlice);
      const std::lock_guard lock(mutex_);
      status_["bus_error"] = "";
    } catch (const std::exception& e) {
      {
        const std::lock_guard lock(mutex_);
        status_["bus_error"] = e.what();
      }
      std::unique_lock lock(mutex_);  // a failing bus is retried, not spun on
      wake_.wait_for(lock, std::chrono::milliseconds(100), [this] { return stopping_; });
    }
    refresh_status();
  }
}

}  // namespace tnv::serve
