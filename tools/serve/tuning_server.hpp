#pragma once
// The live tuning page's HTTP server (cpp-httplib): the page's files, the
// telemetry as Server-Sent Events, and JSON endpoints for parameters,
// faults, motions, captures, the Bode view and browser control. Every
// request that needs the node goes through the NodeWorker; commands and
// changes only from the browser tab that has control. Every request passes
// the AccessGate first (Host, secret, Origin, body) and every state-changing
// one is written to the AuditLog; a tab that stops its heartbeat loses
// control and the motion it started is stopped (the dead-man rule).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "tools/can_emu/emulated_bus.hpp"
#include "tools/can/node_client.hpp"
#include "tools/serve/access_gate.hpp"
#include "tools/serve/audit_log.hpp"
#include "tools/serve/browser_control.hpp"
#include "tools/serve/capture_shelf.hpp"
#include "tools/serve/node_worker.hpp"
#include "tools/serve/param_desk.hpp"
#include "tools/serve/program_state.hpp"
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
  // The dead-man rule: a tab with control that sends no heartbeat (the page
  // sends one every third of this) loses control, and its motion is stopped.
  std::chrono::milliseconds control_deadman{300};
  std::string secret;    // "" = a new one from make_secret() (secret() says which)
  bool read_only = false;  // may watch, never command: every state-changing request 403
  std::string tls_cert;  // both set: HTTPS (required off the loopback)
  std::string tls_key;
  std::string audit_path;  // "" = stderr (the journal under systemd)
  std::size_t max_body_bytes = 64 * 1024;
  // The Program panel's requests (/api/program/*) carry a whole program: their own limit.
  std::size_t max_program_bytes = 4 * 1024 * 1024;
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
  // Serves until stop() (from another thread or a signal watcher); returns
  // at once when stop() came first.
  void listen();
  // Ends listen() wherever it is: cpp-httplib's stop() is lost on a server
  // that has not started accepting yet, so it is repeated until listen() returns.
  void stop();

  std::size_t stream_count() const noexcept { return streams_.load(); }
  NodeWorker& worker() noexcept { return worker_; }
  const std::string& secret() const noexcept { return options_.secret; }
  // The page's address with the secret, as printed: scheme://host:port/?token=SECRET.
  std::string page_url(const std::string& host, int port) const;
  const AuditLog& audit() const noexcept { return audit_; }
  // The page's program run: {"phase", "line", ...} as the telemetry stream carries it.
  nlohmann::json program_state() const { return program_.json(); }

  // One request through the gate and the API's routes in memory, no
  // socket (the fuzz target; the page's own files are not served here).
  // `req.matches` is filled as the server's routing does. Returns the
  // gate's verdict (a refusal is the answer).
  GateVerdict handle(httplib::Request& req, httplib::Response& res);
  // Nothing a refused request may change: who has control and how many
  // jobs the node thread was offered.
  nlohmann::json state_snapshot();

 private:
  using Handler = std::function<void(const httplib::Request&, httplib::Response&)>;
  struct Route {
    std::string method;
    std::regex pattern;
    Handler handler;
  };
  void get(const std::string& pattern, Handler handler);
  void post(const std::string& pattern, Handler handler);
  // Before any route: the gate, and the secret's exchange for a cookie.
  // True when it answered (a refusal or the exchange).
  bool gatekeeper(const httplib::Request& req, httplib::Response& res);
  // A state-changing request and its answer into the audit trail.
  void audited(const httplib::Request& req, const httplib::Response& res, const std::string& session);
  void deadman_loop();
  void routes();
  void node_routes();  // node_routes.cpp
  void program_routes();  // program_routes.cpp
  // A command or a change: only from the tab with control.
  void commanded(const httplib::Request& req, httplib::Response& res,
                 const std::function<nlohmann::json(const nlohmann::json& body)>& f);
  void telemetry_stream(const httplib::Request& req, httplib::Response& res);
  nlohmann::json control_json(const std::string& token);

  can_host::EmulatedBus* emulated_;
  ServeOptions options_;
  AccessGate gate_;
  AuditLog audit_;
  std::vector<Route> routes_;
  ScopeRing ring_;
  NodeWorker worker_;
  BrowserControl control_;
  ParamDesk desk_;  // node thread only (used inside jobs)
  CaptureShelf captures_;
  ProgramState program_;  // the page's program run
  std::unique_ptr<httplib::Server> http_;
  std::atomic<std::size_t> streams_{0};
  std::atomic<bool> stopping_{false};
  std::atomic<bool> page_motion_{false};  // a motion started by the page may be running
  std::mutex deadman_mutex_;
  std::condition_variable deadman_wake_;
  std::thread deadman_;
  std::mutex listen_mutex_;
  std::condition_variable listen_done_;
  bool listen_entered_ = false;   // listen_mutex_ held
  bool listen_returned_ = false;  // listen_mutex_ held
};

}  // namespace tnv::serve
