#include "tools/serve/tuning_server.hpp"

#include <chrono>
#include <future>
#include <memory>

#include "tools/serve/api_error.hpp"
#include "tools/serve/http_reply.hpp"
#include "tools/serve/page_program.hpp"
// Last: <resolv.h>, which it includes, defines the macro _res that Eigen's headers use as a name.
#include <httplib.h>

// The Program panel's endpoints: a program's preview (anyone who may post)
// and its run (the tab with control), whole or from a line (page_canon_setup). Both interpret the program on the
// node thread, with the node's limits from where the table stands.
namespace tnv::serve {

namespace {

// How often the run's handler looks whether its program started streaming.
constexpr std::chrono::milliseconds kStartLook{10};

}  // namespace

void TuningServer::program_routes() {
  post("/api/program/preview", [this](const httplib::Request& req, httplib::Response& res) {
    answer(res, [&] {
      const nlohmann::json body = body_json(req);
      const std::string text = text_field(body, "gcode");
      const gcode::CanonSetup canon = page_canon_setup(body);
      const bool tool_from_node = !body.contains("tool_in_spindle");  // a run from line: the node's tool
      if (program_.active()) throw ApiError(kHttpConflict, "a program is running: preview it when it has ended");
      auto plan = std::make_shared<can_host::ProgramPlan>();
      worker_.run([this, text, canon, tool_from_node, plan](can_host::NodeClient& c) {
        can_host::ProgramRunOptions o;
        o.canon = canon;
        o.tool_from_node = tool_from_node;
        o.on_frame = worker_.scope_listener();
        *plan = can_host::plan_gcode(c, text, o);
        return nlohmann::json();
      });
      if (nlohmann::json refusal = plan_refusal(*plan); !refusal.is_null()) {
        const std::string why = refusal["error"].get<std::string>();
        throw ApiError(kHttpBadRequest, why, std::move(refusal));
      }
      return preview_json(*plan);
    });
  });

  // Answers once the program's elements start going out (or it was
  // refused); its progress and end come with the telemetry stream.
  post("/api/program/run", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json& body) {
      const std::string text = text_field(body, "gcode");
      const gcode::CanonSetup canon = page_canon_setup(body);  // a bad field: 400 before anything starts
      const bool tool_from_node = !body.contains("tool_in_spindle");
      if (!program_.begin(program_summary(text))) throw ApiError(kHttpConflict, "a program is running already");
      std::future<nlohmann::json> done;
      try {
        done = worker_.submit([this, text, canon, tool_from_node](can_host::NodeClient& c) {
          return run_program_for_page(c, text, canon, tool_from_node, program_, worker_.scope_listener());
        });
      } catch (const std::exception& e) {
        program_.finish("refused", e.what());
        throw;
      }
      while (done.wait_for(kStartLook) != std::future_status::ready && !program_.is_streaming()) {
      }
      if (done.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        nlohmann::json result = done.get();  // a refusal throws here (400 with its line, 409, 502)
        result["program"] = program_.json();
        return result;
      }
      return nlohmann::json{{"started", true}, {"program", program_.json()}};
    });
  });

  // The program rests at a pause (M0, M1, M6): go on (COMMAND cycle_start, sent by the run's stream).
  post("/api/program/resume", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json&) {
      if (!program_.resume()) throw ApiError(kHttpConflict, "the program is not paused");
      return program_.json();
    });
  });

  // The feed hold of the running program: {"hold": true} brakes on the path and waits, false goes on
  // (COMMAND feed_hold / feed_resume, sent by the run's stream at its next look).
  post("/api/program/hold", [this](const httplib::Request& req, httplib::Response& res) {
    commanded(req, res, [this](const nlohmann::json& body) {
      if (!body.contains("hold") || !body["hold"].is_boolean()) throw ApiError(kHttpBadRequest, "give \"hold\": true or false");
      if (!program_.feed_hold(body["hold"].get<bool>())) throw ApiError(kHttpConflict, "no program is running");
      return program_.json();
    });
  });

  get("/api/program", [this](const httplib::Request&, httplib::Response& res) {
    answer(res, [&] { return program_.json(); });
  });
}

}  // namespace tnv::serve
