#include "tools/serve/tuning_server.hpp"

#include <algorithm>
#include <stdexcept>
#include <thread>
#include <utility>

#include "tools/serve/api_error.hpp"
#include "tools/serve/http_reply.hpp"
#include "tools/serve/page_files.hpp"
#include "tools/serve/page_motion.hpp"
#include "tools/serve/page_program.hpp"
#include "tools/serve/telemetry_sample.hpp"
// Last: <resolv.h>, which it includes, defines the macro _res that Eigen's headers use as a name.
#include <httplib.h>

namespace tnv::serve {

namespace {

using Clock = std::chrono::steady_clock;
// Handler threads: two browsers each hold a telemetry stream and up to six
// keep-alive connections; the pool must not run dry.
constexpr std::size_t kHttpThreads = 32;

// Holds one of the server's telemetry stream slots while a stream lives;
// `on_close` runs when it ends (the tab closed or reloaded).
struct StreamSlot {
  StreamSlot(std::atomic<std::size_t>& count, std::function<void()> on_close)
      : count_(count), on_close_(std::move(on_close)) {}
  ~StreamSlot() {
    --count_;
    if (on_close_) on_close_();
  }
  StreamSlot(const StreamSlot&) = delete;
  StreamSlot& operator=(const StreamSlot&) = delete;
  std::atomic<std::size_t>& count_;
  std::function<void()> on_close_;
};

nlohmann::json batch_json(const std::vector<ScopeSample>& samples) {
  nlohmann::json t = nlohmann::json::array();
  nlohmann::json v = nlohmann::json::array();
  for (const ScopeSample& s : samples) {
    t.push_back(s.t_s);
    v.push_back(s.values);  // NaN (channel not streamed) becomes null
  }
  return {{"t", t}, {"v", v}};
}

ServeOptions with_secret(ServeOptions o) {
  if (o.secret.empty()) o.secret = make_secret();
  return o;
}

GateOptions gate_options(const ServeOptions& o) {
  GateOptions g;
  g.secret = o.secret;
  g.bind = o.bind;
  g.port = o.port;
  g.tls = !o.tls_cert.empty();
  g.read_only = o.read_only;
  g.max_body_bytes = o.max_body_bytes;
  g.max_program_bytes = o.max_program_bytes;
  return g;
}

std::unique_ptr<httplib::Server> make_http(const ServeOptions& o) {
  if (const std::string why = bind_refusal(o.bind, o.tls_cert, o.tls_key); !why.empty()) throw std::runtime_error(why);
  if (o.tls_cert.empty()) return std::make_unique<httplib::Server>();
  auto s = std::make_unique<httplib::SSLServer>(o.tls_cert.c_str(), o.tls_key.c_str());
  if (!s->is_valid())
    throw std::runtime_error("cannot load the TLS certificate " + o.tls_cert + " and key " + o.tls_key);
  return s;
}

// The motions that keep the table moving after the request returns.
bool lasting_motion(const std::string& body) {
  const nlohmann::json j = nlohmann::json::parse(body, nullptr, false);
  if (!j.is_object() || !j.contains("kind") || !j["kind"].is_string()) return false;
  const std::string kind = j["kind"].get<std::string>();
  return kind == "move" || kind == "circle";
}

}  // namespace

TuningServer::TuningServer(can_host::NodeClient& client, can_host::EmulatedBus* emulated, ServeOptions options)
    : emulated_(emulated),
      options_(with_secret(std::move(options))),
      gate_(gate_options(options_)),
      audit_(options_.audit_path),
      ring_(options_.history_samples),
      worker_(client, emulated, ring_, options_.max_pending_jobs),
      control_(options_.control_deadman),
      captures_(options_.max_captures),
      http_(make_http(options_)) {
  http_->new_task_queue = [] { return new httplib::ThreadPool(kHttpThreads); };
  http_->set_keep_alive_timeout(2);
  http_->set_payload_max_length(std::max(options_.max_body_bytes, options_.max_program_bytes));
  http_->set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    return gatekeeper(req, res) ? httplib::Server::HandlerResponse::Handled
                                : httplib::Server::HandlerResponse::Unhandled;
  });
  routes();
}

TuningServer::~TuningServer() {
  stop();
  worker_.stop();
}

std::string TuningServer::page_url(const std::string& host, int port) const {
  const std::string h = host.find(':') != std::string::npos ? "[" + host + "]" : host;
  return std::string(options_.tls_cert.empty() ? "http" : "https") + "://" + h + ":" + std::to_string(port) +
         "/?token=" + options_.secret;
}

void TuningServer::get(const std::string& pattern, Handler handler) {
  http_->Get(pattern, handler);
  routes_.push_back({"GET", std::regex(pattern), std::move(handler)});
}

void TuningServer::post(const std::string& pattern, Handler handler) {
  // Audited here, with the body read and the answer not yet compressed for the wire.
  Handler logged = [this, handler = std::move(handler)](const httplib::Request& req, httplib::Response& res) {
    // A chunked body has no length in its headers: its route's limit is checked here, once read.
    if (const std::size_t limit = gate_.body_limit(req.path); req.body.size() > limit)
      reply(res, 413, {{"error", "the request body is over " + std::to_string(limit) + " bytes"}});
    else
      handler(req, res);
    audited(req, res, gate_.check(req).session);
  };
  http_->Post(pattern, logged);
  routes_.push_back({"POST", std::regex(pattern), std::move(logged)});
}

bool TuningServer::gatekeeper(const httplib::Request& req, httplib::Response& res) {
  const GateVerdict v = gate_.check(req);
  if (!v.ok()) {
    reply(res, v.status, {{"error", v.reason}});
    audited(req, res, v.session);  // the body is not read yet: refused on its headers
    return true;
  }
  // The printed URL: the secret is exchanged for a session cookie and
  // dropped from the address bar (and from the browser's history).
  if (req.method == "GET" && req.path == "/" && req.has_param("token")) {
    const std::string session = gate_.open_session(req.get_param_value("token"));
    audit_.event(session.empty() ? "wrong token in the page's URL" : "session opened", req.remote_addr);
    if (session.empty()) {
      res.status = 401;
      res.set_content("This is not the URL tnvctl serve printed at its start: the token is wrong "
                      "(it changes at every start).\n", "text/plain");
      return true;
    }
    res.set_header("Set-Cookie", gate_.set_cookie(session));
    res.set_header("Cache-Control", "no-store");
    res.set_redirect("/", 303);
    return true;
  }
  return false;
}

void TuningServer::audited(const httplib::Request& req, const httplib::Response& res, const std::string& session) {
  if (req.method == "GET" || req.method == "HEAD") return;
  if (req.path == "/api/control/heartbeat" && res.status == 200) return;  // ten a second: only a refused one
  if (req.path.rfind("/api/program/", 0) == 0) {  // a program's size, lines and digest, not its text
    const nlohmann::json body = nlohmann::json::parse(req.body, nullptr, false);
    if (body.is_object() && body.contains("gcode") && body["gcode"].is_string()) {
      nlohmann::json logged = body;  // the other fields (a run from line, the switches) as sent
      for (const char* text : {"gcode", "tool_table", "var_file"})  // files: their size, lines and digest
        if (body.contains(text) && body[text].is_string()) logged[text] = program_summary(body[text].get<std::string>());
      audit_.request(req, res, session, logged);
      return;
    }
  }
  audit_.request(req, res, session);
}

GateVerdict TuningServer::handle(httplib::Request& req, httplib::Response& res) {
  const GateVerdict verdict = gate_.check(req);
  if (!gatekeeper(req, res)) {
    bool found = false;
    for (const Route& r : routes_) {
      if (r.method != req.method || !std::regex_match(req.path, req.matches, r.pattern)) continue;
      r.handler(req, res);
      found = true;
      break;
    }
    if (!found) reply(res, kHttpNotFound, {{"error", "no such route"}});
  }
  if (res.status == -1) res.status = 200;  // as cpp-httplib's server does for a handled request (a stream)
  return verdict;
}

nlohmann::json TuningServer::state_snapshot() {
  const auto now = Clock::now();
  return {{"control_taken", control_.anyone_holds(now)}, {"jobs_offered", worker_.jobs_offered()},
          {"page_motion", page_motion_.load()}};
}

void TuningServer::deadman_loop() {
  std::unique_lock lock(deadman_mutex_);
  while (!stopping_) {
    deadman_wake_.wait_for(lock, options_.control_deadman / 6);
    if (stopping_) break;
    const std::string gone = control_.lapse(Clock::now());
    if (gone.empty()) continue;
    // A program's stream is told at once; the stop job runs after its job.
    const bool program = program_.interrupt();
    const bool moving = page_motion_.exchange(false) || program;
    lock.unlock();
    std::string what = "tab " + gone.substr(0, 8) + "... went quiet: control ended";
    try {
      const nlohmann::json done = worker_.run([moving](can_host::NodeClient& c) {
        std::string refused;
        if (moving) {
          try {
            start_motion(c, MotionRequest{"stop"});
          } catch (const std::exception& e) {  // refused (nothing moving any more): the release still follows
            refused = e.what();
          }
        }
        c.release_ownership_if_taken();
        return nlohmann::json{{"refused", refused}};
      });
      if (program) what += ", its program interrupted";
      if (moving) what += done["refused"] == "" ? ", its motion stopped" : ", stop refused: " + done["refused"].get<std::string>();
    } catch (const std::exception& e) {
      what += std::string(", the stop failed: ") + e.what();
    }
    audit_.event("dead-man", what);
    lock.lock();
  }
}
int TuningServer::start() {
  if (const std::string missing = missing_page_library(options_.js_dir); !missing.empty())
    throw std::runtime_error(missing);
  if (!http_->set_mount_point("/", options_.web_dir))
    throw std::runtime_error("the page's files are missing: no directory " + options_.web_dir);
  http_->set_mount_point("/js/chart.js", options_.js_dir + "/chart.js");
  int port = options_.port;
  if (port == 0) port = http_->bind_to_any_port(options_.bind);
  else if (!http_->bind_to_port(options_.bind, port)) port = -1;
  if (port <= 0) {
    std::string message = "cannot listen on ";
    message.append(options_.bind).append(":").append(std::to_string(options_.port));
    throw std::runtime_error(message.append(" (address in use, or not this machine's)"));
  }
  gate_.set_port(port);
  worker_.start();
  if (!deadman_.joinable()) deadman_ = std::thread([this] { deadman_loop(); });
  return port;
}

void TuningServer::listen() {
  {
    const std::lock_guard lock(listen_mutex_);
    if (stopping_) return;
    listen_entered_ = true;
  }
  http_->listen_after_bind();
  const std::lock_guard lock(listen_mutex_);
  listen_returned_ = true;
  listen_done_.notify_all();
}

void TuningServer::stop() {
  program_.interrupt();  // the node thread's join must not wait for a program's end
  {
    const std::lock_guard lock(deadman_mutex_);
    stopping_ = true;
  }
  deadman_wake_.notify_all();
  {
    std::unique_lock lock(listen_mutex_);
    stopping_ = true;  // under this mutex too: listen() has either seen it or entered
    do {
      lock.unlock();
      http_->stop();
      lock.lock();
    } while (listen_entered_ && !listen_done_.wait_for(lock, std::chrono::milliseconds(5), [this] { return listen_returned_; }));
  }
  if (deadman_.joinable() && deadman_.get_id() != std::this_thread::get_id()) deadman_.join();
}

nlohmann::json TuningServer::control_json(const std::string& token) {
  const auto now = Clock::now();
  return {{"you", control_.holds(token, now)}, {"taken", control_.anyone_holds(now)}};
}

void TuningServer::commanded(const httplib::Request& req, httplib::Response& res,
                             const std::function<nlohmann::json(const nlohmann::json& body)>& f) {
  answer(res, [&] {
    if (const std::string why = control_.check(req.get_header_value(kTokenHeader), Clock::now()); !why.empty())
      throw ApiError(kHttpForbidden, why);
    const nlohmann::json body = body_json(req);
    nlohmann::json answer = f(body);
    if (req.path == "/api/motion") page_motion_ = lasting_motion(req.body);
    return answer;
  });
}

void TuningServer::telemetry_stream(const httplib::Request& req, httplib::Response& res) {
  if (streams_.fetch_add(1) >= options_.max_streams) {
    --streams_;
    reply(res, kHttpUnavailable, {{"error", "too many telemetry streams open: close a page"}});
    return;
  }
  const std::string token = req.has_param("token") ? req.get_param_value("token") : "";
  // A closed tab is gone at once: the dead-man stop need not wait for the missed heartbeats.
  auto slot = std::make_shared<StreamSlot>(streams_, [this, token] {
    control_.gone(token);
    deadman_wake_.notify_all();
  });
  auto cursor = std::make_shared<std::uint64_t>(0);  // the first batch carries the whole history
  auto last_sent = std::make_shared<Clock::time_point>();
  res.set_header("Cache-Control", "no-cache");
  res.set_chunked_content_provider(
      "text/event-stream", [this, slot, token, cursor, last_sent](std::size_t, httplib::DataSink& sink) {
        if (stopping_) return false;
        // At most one event per min_batch_period; then the next sample, or status alone after 200 ms.
        const auto next = *last_sent + options_.min_batch_period;
        if (const auto now = Clock::now(); now < next) std::this_thread::sleep_for(next - now);
        ring_.wait_newer(*cursor, std::chrono::milliseconds(200));
        if (stopping_) return false;
        const std::vector<ScopeSample> samples = ring_.since(*cursor, ring_.capacity());
        if (!samples.empty()) *cursor = samples.back().seq;
        nlohmann::json event = batch_json(samples);
        event["status"] = worker_.status();
        event["control"] = control_json(token);
        event["program"] = program_.json();
        const std::string text = "data: " + json_text(event) + "\n\n";
        *last_sent = Clock::now();
        return sink.write(text.data(), text.size());
      });
}

void TuningServer::routes() {
  get("/api/info", [this](const httplib::Request&, httplib::Response& res) {
    answer(res, [&] {
      nlohmann::json channels = nlohmann::json::array();
      for (const ScopeChannel& c : kScopeChannels) channels.push_back({{"name", c.name}, {"unit", c.unit}});
      nlohmann::json info = options_.info;
      info["channels"] = channels;
      info["history_samples"] = ring_.capacity();
      info["deadman_ms"] = options_.control_deadman.count();
      info["read_only"] = options_.read_only;
      return info;
    });
  });
  get("/api/telemetry", [this](const httplib::Request& req, httplib::Response& res) { telemetry_stream(req, res); });
  get("/api/status", [this](const httplib::Request&, httplib::Response& res) {
    answer(res, [&] { return worker_.status(); });
  });

  // Browser control.
  get("/api/control", [this](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] { return control_json(req.get_header_value(kTokenHeader)); });
  });
  post("/api/control/take", [this](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const std::string token = req.get_header_value(kTokenHeader);
      if (const std::string why = control_.take(token, Clock::now()); !why.empty()) throw ApiError(kHttpConflict, why);
      return control_json(token);
    });
  });
  post("/api/control/release", [this](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const std::string token = req.get_header_value(kTokenHeader);
      // Released by the page, the node is free for another host too (tnvctl --host-id 2 autotune ...).
      if (control_.release(token)) {
        program_.interrupt();  // nobody's program runs on: stopped on its path
        worker_.run([](can_host::NodeClient& c) {
          c.release_ownership_if_taken();
          return nlohmann::json();
        });
      }
      return control_json(token);
    });
  });
  // The dead-man rule's heartbeat: the page sends it every third of the
  // dead-man time while it has control.
  post("/api/control/heartbeat", [this](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const std::string token = req.get_header_value(kTokenHeader);
      if (!control_.seen(token, Clock::now())) throw ApiError(kHttpForbidden, "this tab does not have control");
      return control_json(token);
    });
  });

  node_routes();
  program_routes();
}

}  // namespace tnv::serve
