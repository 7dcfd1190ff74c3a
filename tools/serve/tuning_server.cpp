#include "tools/serve/tuning_server.hpp"

#include <httplib.h>

#include <stdexcept>
#include <thread>

#include "tools/can/capture_run.hpp"
#include "tools/can/host_bus.hpp"
#include "tools/can/motion_run.hpp"
#include "tools/can/request_error.hpp"
#include "tools/serve/api_error.hpp"
#include "tools/serve/freq_response_for_page.hpp"
#include "tools/serve/page_files.hpp"
#include "tools/serve/page_motion.hpp"
#include "tools/serve/telemetry_sample.hpp"

namespace tnv::serve {

namespace {

using Clock = std::chrono::steady_clock;
constexpr const char* kJson = "application/json";
constexpr const char* kTokenHeader = "X-Tnv-Token";
// After the stop, the recording must be done within this (it is at once).
constexpr can_host::Micros kCaptureWait{5'000'000};
// Handler threads: two browsers each hold a telemetry stream and up to six
// keep-alive connections; the pool must not run dry.
constexpr std::size_t kHttpThreads = 32;

void reply(httplib::Response& res, int status, const nlohmann::json& body) {
  res.status = status;
  res.set_content(body.dump(), kJson);
}

// Runs `f`; its failures become the HTTP status and {"error": reason}.
void answer(httplib::Response& res, const std::function<nlohmann::json()>& f) {
  try {
    reply(res, 200, f());
  } catch (const ApiError& e) {
    reply(res, e.status(), {{"error", e.what()}});
  } catch (const can_host::RequestError& e) {
    reply(res, e.kind() == can_host::RequestError::Kind::refused ? kHttpConflict : kHttpBadGateway, {{"error", e.what()}});
  } catch (const can_host::MotionFailed& e) {
    reply(res, kHttpConflict, {{"error", e.what()}});
  } catch (const std::invalid_argument& e) {
    reply(res, kHttpBadRequest, {{"error", e.what()}});
  } catch (const nlohmann::json::exception& e) {  // a field of the wrong type in the request body
    reply(res, kHttpBadRequest, {{"error", std::string("bad request body: ") + e.what()}});
  } catch (const can_host::BusError& e) {
    reply(res, kHttpBadGateway, {{"error", e.what()}});
  } catch (const can_host::CaptureError& e) {
    reply(res, kHttpBadGateway, {{"error", e.what()}});
  } catch (const std::exception& e) {
    reply(res, 500, {{"error", e.what()}});
  }
}

nlohmann::json body_json(const httplib::Request& req) {
  if (req.body.empty()) return nlohmann::json::object();
  nlohmann::json j = nlohmann::json::parse(req.body, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw ApiError(kHttpBadRequest, "the request body is not a JSON object");
  return j;
}

std::string text_field(const nlohmann::json& body, const char* key) {
  if (!body.contains(key) || !body[key].is_string()) throw ApiError(kHttpBadRequest, std::string("give \"") + key + "\"");
  return body[key].get<std::string>();
}

int capture_id(const httplib::Request& req) {
  try {
    return std::stoi(req.matches[1].str());
  } catch (const std::exception&) {
    throw ApiError(kHttpBadRequest, "bad capture id");
  }
}

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

  // Parameters: anyone reads, the tab with control changes.
  s.Get("/api/params", [this](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const std::string filter = req.has_param("filter") ? req.get_param_value("filter") : "";
      return worker_.run([this, filter](can_host::NodeClient& c) {
        return nlohmann::json{{"params", desk_.list(c, filter)}, {"staged", desk_.staged_json()}};
      });
    });
  });
  s.Post("/api/params/set", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json& body) {
      const std::string name = text_field(body, "name");
      const nlohmann::json value = body.value("value", nlohmann::json());
      ParamDesk::parse(name, value);  // bad input is refused here, before the node's queue
      return worker_.run([this, name, value](can_host::NodeClient& c) { return desk_.set(c, name, value); });
    });
  });
  s.Post("/api/params/stage", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json& body) {
      const std::string name = text_field(body, "name");
      const nlohmann::json value = body.value("value", nlohmann::json());
      ParamDesk::parse(name, value);
      return worker_.run([this, name, value](can_host::NodeClient& c) { return desk_.stage(c, name, value); });
    });
  });
  s.Post("/api/params/commit", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json&) {
      return worker_.run([this](can_host::NodeClient& c) { return desk_.commit(c); });
    });
  });
  s.Post("/api/params/discard", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json&) {
      return worker_.run([this](can_host::NodeClient& c) { return desk_.discard(c); });
    });
  });

  // Faults and motions.
  s.Post("/api/fault/clear", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json&) {
      return worker_.run([](can_host::NodeClient& c) { return clear_faults_for_page(c); });
    });
  });
  s.Post("/api/motion", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json& body) {
      const MotionRequest motion = parse_motion_request(body, emulated_);
      return worker_.run([motion](can_host::NodeClient& c) { return start_motion(c, motion); });
    });
  });

  // Captures: taken by the tab with control, listed and downloaded by anyone.
  s.Post("/api/captures", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json& body) {
      can_host::CaptureSetup setup;
      setup.channels = body.value("channels", std::string());
      setup.trigger = "immediate";  // recorded now: the page's motions start separately
      setup.decimation = body.value("decimation", 0);
      can_host::check_capture_setup(setup);
      const double duration_s = body.value("duration_s", 2.0);
      if (!(duration_s >= 0.01 && duration_s <= 60.0))
        throw ApiError(kHttpBadRequest, "duration_s must be in [0.01, 60] s");
      const can_host::Micros duration{static_cast<long long>(duration_s * 1e6)};
      // The table comes back beside the job's JSON: the node thread fills it, this handler shelves it.
      auto table = std::make_shared<can_host::CaptureTable>();
      nlohmann::json result = worker_.run([setup, duration, table](can_host::NodeClient& c) {
        can_host::arm_capture(c, setup);
        can_host::stop_capture_after(c, duration);  // the buffer would hold minutes: record what was asked
        can_host::DownloadedCapture d = can_host::download_capture(c, kCaptureWait);
        *table = std::move(d.table);
        return nlohmann::json{{"samples", table->samples()}, {"upload_s", d.upload_s}};
      });
      result["id"] = captures_.add(std::move(*table));
      return result;
    });
  });
  s.Get("/api/captures", [this](const httplib::Request&, httplib::Response& res) {
    answer(res, [&] { return nlohmann::json{{"captures", captures_.list()}}; });
  });
  s.Get(R"(/api/captures/(\d+))", [this](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      std::optional<nlohmann::json> c = captures_.columns(capture_id(req));
      if (!c) throw ApiError(kHttpNotFound, "no such capture (the server keeps the last " +
                                                std::to_string(options_.max_captures) + ")");
      return *c;
    });
  });
  s.Get(R"(/api/captures/(\d+)\.csv)", [this](const httplib::Request& req, httplib::Response& res) {
    const int id = capture_id(req);
    const std::optional<std::string> csv = captures_.csv(id);
    if (!csv) return reply(res, kHttpNotFound, {{"error", "no such capture"}});
    res.set_header("Content-Disposition", "attachment; filename=\"capture-" + std::to_string(id) + ".csv\"");
    res.set_content(*csv, "text/csv");
  });

  // The Bode view's measurement.
  s.Post("/api/freq-response", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json& body) {
      const FreqResponseRequest request = parse_freq_response_request(body);
      return worker_.run([request](can_host::NodeClient& c) { return freq_response_for_page(c, request); });
    });
  });
}

}  // namespace tnv::serve
