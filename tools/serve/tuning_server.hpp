#pragma once
// The live tuning page's HTTP server (cpp-httplib): the page's files, the
// telemetry as Server-Sent Events, and JSON endpoints for parameters,
// faults, motions, captures, the Bode view and browser control. Every
// request that needs the node goes through the NodeWorker; commands and
// changes only from the browser tab that has control.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "tools/can_emu/emulated_bus.hpp"
#include "tools/can/node_client.hpp"
#include "tools/serve/browser_control.hpp"
#include "tools/serve/capture_shelf.hpp"
#include "tools/serve/node_worker.hpp"
#include "tools/serve/param_desk.hpp"
#include "tools/serve/scope_ring.hpp"

namespace httplib {
class Server;
struct Request;
struct Response;
}  // namespace httplib

namespace tnv::serve {

struct ServeOptions {
  std::string bind = "127.0.0.1";  // a motion controller's page is not open to the network by default
  int port = 0;                    // 0: any free port (bind() says which)
  std::string web_dir;             // index.html, style.css and the page's scripts
  std::string js_dir;              // holds chart.js/chart.min.js
  std::size_t history_samples = 2048;  // > 10 s of TLM_POSITION at its default 10 ms
  std::size_t max_pending_jobs = 16;
  std::size_t max_streams = 8;
  std::size_t max_captures = 8;
  std::chrono::milliseconds min_batch_period{10};  // at most 100 telemetry events/s per stream
  std::chrono::milliseconds control_idle_release{10'000};
  nlohmann::json info = nlohmann::json::object();  // shown in the page's header (node, bus)
};

class TuningServer {
 public:
  TuningServer(can_host::NodeClient& client, can_host::EmulatedBus* emulated, ServeOptions options);
  ~TuningServer();
  TuningServer(const TuningServer&) = delete;
  TuningServer& operator=(const TuningServer&) = delete;

  // Starts the node thread and binds; returns the port. Throws
  // std::runtime_error naming the address when it cannot bind.
  int start();
  // Serves until stop() (from another thread or a signal watcher).
  void listen();
  void stop();

  std::size_t stream_count() const noexcept { return streams_.load(); }
  NodeWorker& worker() noexcept { return worker_; }

 private:
  void routes();
  void node_routes();  // node_routes.cpp
  // A command or a change: only from the tab with control.
  void commanded(const httplib::Request& req, httplib::Response& res,
                 const std::function<nlohmann::json(const nlohmann::json& body)>& f);
  void telemetry_stream(const httplib::Request& req, httplib::Response& res);
  nlohmann::json control_json(const std::string& token);

  can_host::EmulatedBus* emulated_;
  ServeOptions options_;
  ScopeRing ring_;
  NodeWorker worker_;
  BrowserControl control_;
  ParamDesk desk_;  // node thread only (used inside jobs)
  CaptureShelf captures_;
  std::unique_ptr<httplib::Server> http_;
  std::atomic<std::size_t> streams_{0};
  std::atomic<bool> stopping_{false};
};

}  // namespace tnv::serve
