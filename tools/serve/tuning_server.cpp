#include "tools/serve/tuning_server.hpp"

#include <stdexcept>
#include <thread>

#include "tools/serve/api_error.hpp"
#include "tools/serve/http_reply.hpp"
#include "tools/serve/page_files.hpp"
#include "tools/serve/telemetry_sample.hpp"
// Last: <resolv.h>, which it includes, defines the macro _res that Eigen's headers use as a name.
#include <httplib.h>

namespace tnv::serve {

namespace {

using Clock = std::chrono::steady_clock;
// Handler threads: two browsers each hold a telemetry stream and up to six
// keep-alive connections; the pool must not run dry.
constexpr std::size_t kHttpThreads = 32;

// Holds one of the server's telemetry stream slots while a stream lives.
struct StreamSlot {
  explicit StreamSlot(std::atomic<std::size_t>& count) : count_(count) {}
  ~StreamSlot() { --count_; }
  StreamSlot(const StreamSlot&) = delete;
  StreamSlot& operator=(const StreamSlot&) = delete;
  std::atomic<std::size_t>& count_;
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

}  // namespace

TuningServer::TuningServer(can_host::NodeClient& client, can_host::EmulatedBus* emulated, ServeOptions options)
    : emulated_(emulated),
      options_(std::move(options)),
      ring_(options_.history_samples),
      worker_(client, emulated, ring_, options_.max_pending_jobs),
      control_(options_.control_idle_release),
      captures_(options_.max_captures),
      http_(std::make_unique<httplib::Server>()) {
  http_->new_task_queue = [] { return new httplib::ThreadPool(kHttpThreads); };
  http_->set_keep_alive_timeout(2);
  routes();
}

TuningServer::~TuningServer() {
  stop();
  worker_.stop();
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
  worker_.start();
  return port;
}

void TuningServer::listen() { http_->listen_after_bind(); }

void TuningServer::stop() {
  stopping_ = true;
  http_->stop();
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
    return f(body);
  });
}

void TuningServer::telemetry_stream(const httplib::Request& req, httplib::Response& res) {
  if (streams_.fetch_add(1) >= options_.max_streams) {
    --streams_;
    reply(res, kHttpUnavailable, {{"error", "too many telemetry streams open: close a page"}});
    return;
  }
  auto slot = std::make_shared<StreamSlot>(streams_);
  const std::string token = req.has_param("token") ? req.get_param_value("token") : "";
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
        control_.seen(token, Clock::now());
        nlohmann::json event = batch_json(samples);
        event["status"] = worker_.status();
        event["control"] = control_json(token);
        const std::string text = "data: " + event.dump() + "\n\n";
        *last_sent = Clock::now();
        return sink.write(text.data(), text.size());
      });
}

void TuningServer::routes() {
  httplib::Server& s = *http_;
  s.Get("/api/info", [this](const httplib::Request&, httplib::Response& res) {
    answer(res, [&] {
      nlohmann::json channels = nlohmann::json::array();
      for (const ScopeChannel& c : kScopeChannels) channels.push_back({{"name", c.name}, {"unit", c.unit}});
      nlohmann::json info = options_.info;
      info["channels"] = channels;
      info["history_samples"] = ring_.capacity();
      return info;
    });
  });
  s.Get("/api/telemetry", [this](const httplib::Request& req, httplib::Response& res) { telemetry_stream(req, res); });
  s.Get("/api/status", [this](const httplib::Request&, httplib::Response& res) {
    answer(res, [&] { return worker_.status(); });
  });

  // Browser control.
  s.Get("/api/control", [this](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] { return control_json(req.get_header_value(kTokenHeader)); });
  });
  s.Post("/api/control/take", [this](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const std::string token = req.get_header_value(kTokenHeader);
      if (const std::string why = control_.take(token, Clock::now()); !why.empty()) throw ApiError(kHttpConflict, why);
      return control_json(token);
    });
  });
  s.Post("/api/control/release", [this](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const std::string token = req.get_header_value(kTokenHeader);
      // Released by the page, the node is free for another host too (tnvctl --host-id 2 autotune ...).
      if (control_.release(token))
        worker_.run([](can_host::NodeClient& c) {
          c.release_ownership_if_taken();
          return nlohmann::json();
        });
      return control_json(token);
    });
  });

  node_routes();
}

}  // namespace tnv::serve
