#pragma once
// The one thread that talks to the node. NodeClient is not thread-safe (one
// bus, one reply awaited at a time, one tag sequence), so HTTP handlers
// never touch it: they hand a job to this thread through a bounded queue
// and wait for its result. Between jobs the thread receives the node's
// frames; every TLM_POSITION adds a scope sample to the ring, also while a
// long job (a capture upload) is running.
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "tools/can_emu/emulated_bus.hpp"
#include "tools/can/node_client.hpp"
#include "tools/can/telemetry_view.hpp"
#include "tools/serve/scope_ring.hpp"

namespace tnv::serve {

class NodeWorker {
 public:
  using Job = std::function<nlohmann::json(can_host::NodeClient&)>;

  // `emulated`: the in-process node (paced to the wall clock while the
  // worker runs), or nullptr on a real bus.
  NodeWorker(can_host::NodeClient& client, can_host::EmulatedBus* emulated, ScopeRing& ring,
             std::size_t max_pending_jobs);
  ~NodeWorker();
  NodeWorker(const NodeWorker&) = delete;
  NodeWorker& operator=(const NodeWorker&) = delete;

  void start();
  // Ends the thread; jobs still queued fail with ApiError(503).
  void stop();

  // Runs `job` on the node thread and returns its result; its exception is
  // rethrown here. A full queue throws ApiError(503) at once (nothing queued).
  nlohmann::json run(Job job);
  // The same without waiting: the result when the job is done (a program
  // run, whose handler answers once it started).
  std::future<nlohmann::json> submit(Job job);
  // The scope's own listener, for a job that listens to the node itself
  // (node thread only; it is put back after every job anyway).
  can_host::FrameListener scope_listener();
  std::size_t pending() const;
  // How many jobs run() was given so far (run or refused): a refused
  // request must leave this unchanged.
  std::size_t jobs_offered() const noexcept { return offered_.load(); }

  // The latest heartbeat and fault event as the page shows them:
  // {"heartbeat": {...} | null, "fault": {...} | null, "bus_error": ""}.
  nlohmann::json status() const;

 private:
  struct Pending {
    Job job;
    std::promise<nlohmann::json> result;
  };
  void loop();
  void take_frame(const hal::CanFrame& frame, fw::can::MessageId id);
  void refresh_status();

  can_host::NodeClient& client_;
  can_host::EmulatedBus* emulated_;
  ScopeRing& ring_;
  std::size_t max_pending_;
  can_host::TelemetryView view_;  // node thread only
  can_host::Micros started_{0};

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Pending> jobs_;
  bool stopping_ = false;
  nlohmann::json status_;
  std::thread thread_;
  std::atomic<std::size_t> offered_{0};
};

}  // namespace tnv::serve
