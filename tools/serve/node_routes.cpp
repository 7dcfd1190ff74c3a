#include "tools/serve/tuning_server.hpp"

#include "tools/can/capture_run.hpp"
#include "tools/serve/api_error.hpp"
#include "tools/serve/freq_response_for_page.hpp"
#include "tools/serve/http_reply.hpp"
#include "tools/serve/page_motion.hpp"
// Last: <resolv.h>, which it includes, defines the macro _res that Eigen's headers use as a name.
#include <httplib.h>

// The endpoints that talk to the node: parameters, faults and motions,
// captures, the Bode view's measurement. Each runs on the node thread.
namespace tnv::serve {

namespace {

// After the stop, the recording must be done within this (it is at once).
constexpr can_host::Micros kCaptureWait{5'000'000};

int capture_id(const httplib::Request& req) {
  try {
    return std::stoi(req.matches[1].str());
  } catch (const std::exception&) {
    throw ApiError(kHttpBadRequest, "bad capture id");
  }
}

}  // namespace

void TuningServer::node_routes() {
  // Parameters: anyone reads, the tab with control changes.
  get("/api/params", [this](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const std::string filter = req.has_param("filter") ? req.get_param_value("filter") : "";
      return worker_.run([this, filter](can_host::NodeClient& c) {
        return nlohmann::json{{"params", desk_.list(c, filter)}, {"staged", desk_.staged_json()}};
      });
    });
  });
  post("/api/params/set", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json& body) {
      const std::string name = text_field(body, "name");
      const nlohmann::json value = body.value("value", nlohmann::json());
      ParamDesk::parse(name, value);  // bad input is refused here, before the node's queue
      return worker_.run([this, name, value](can_host::NodeClient& c) { return desk_.set(c, name, value); });
    });
  });
  post("/api/params/stage", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json& body) {
      const std::string name = text_field(body, "name");
      const nlohmann::json value = body.value("value", nlohmann::json());
      ParamDesk::parse(name, value);
      return worker_.run([this, name, value](can_host::NodeClient& c) { return desk_.stage(c, name, value); });
    });
  });
  post("/api/params/commit", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json&) {
      return worker_.run([this](can_host::NodeClient& c) { return desk_.commit(c); });
    });
  });
  post("/api/params/discard", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json&) {
      return worker_.run([this](can_host::NodeClient& c) { return desk_.discard(c); });
    });
  });

  // Faults and motions.
  post("/api/fault/clear", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json&) {
      return worker_.run([](can_host::NodeClient& c) { return clear_faults_for_page(c); });
    });
  });
  post("/api/motion", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json& body) {
      const MotionRequest motion = parse_motion_request(body, emulated_);
      const bool halt = motion.kind == "stop" || motion.kind == "estop";
      // A stop reaches a running program at once (its stream's interrupt flag); the command
      // itself follows on the node thread as soon as the program's job has stopped the table.
      // An e-stop does not wait for that: the program's job sends it at its next look.
      const bool interrupted = halt && program_.interrupt(motion.kind == "estop");
      if (!halt && program_.active()) throw ApiError(kHttpConflict, "a program is running: Stop it first");
      nlohmann::json done = worker_.run([motion, interrupted](can_host::NodeClient& c) {
        try {
          return start_motion(c, motion);
        } catch (const ApiError& e) {
          // Stopped on its path the table already holds: the node's refusal of a second stop is no failure.
          if (!interrupted || e.status() != kHttpConflict) throw;
          return nlohmann::json{{"kind", motion.kind}, {"refused", e.what()}};
        }
      });
      if (interrupted) done["program"] = "interrupted";
      return done;
    });
  });

  // Captures: taken by the tab with control, listed and downloaded by anyone.
  post("/api/captures", [this](const httplib::Request& req, httplib::Response& res) {
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
  get("/api/captures", [this](const httplib::Request&, httplib::Response& res) {
    answer(res, [&] { return nlohmann::json{{"captures", captures_.list()}}; });
  });
  get(R"(/api/captures/(\d+))", [this](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      std::optional<nlohmann::json> c = captures_.columns(capture_id(req));
      if (!c) throw ApiError(kHttpNotFound, "no such capture (the server keeps the last " +
                                                std::to_string(options_.max_captures) + ")");
      return *c;
    });
  });
  get(R"(/api/captures/(\d+)\.csv)", [this](const httplib::Request& req, httplib::Response& res) {
    const int id = capture_id(req);
    const std::optional<std::string> csv = captures_.csv(id);
    if (!csv) return reply(res, kHttpNotFound, {{"error", "no such capture"}});
    res.set_header("Content-Disposition", "attachment; filename=\"capture-" + std::to_string(id) + ".csv\"");
    res.set_content(*csv, "text/csv");
  });

  // The Bode view's measurement.
  post("/api/freq-response", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json& body) {
      FreqResponseRequest request = parse_freq_response_request(body);
      if (emulated_ != nullptr) {  // the model side on the emulated table's own plant, as tnvctl --emu does
        const emu::AxisPlantParams& p = emulated_->scenario().plant[request.axis == "y" ? 1 : 0];
        request.plant_model = fw::zoh_axis_model(p.tau_s, p.gain, fw::kControlPeriod_s);
      }
      return worker_.run([request](can_host::NodeClient& c) { return freq_response_for_page(c, request); });
    });
  });
}

}  // namespace tnv::serve
