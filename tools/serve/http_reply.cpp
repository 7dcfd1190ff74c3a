#include "tools/serve/http_reply.hpp"

#include "tools/can/capture_run.hpp"
#include "tools/can/host_bus.hpp"
#include "tools/can/motion_run.hpp"
#include "tools/can/request_error.hpp"
#include "tools/serve/api_error.hpp"
// Last: <resolv.h>, which it includes, defines the macro _res that Eigen's headers use as a name.
#include <httplib.h>

namespace tnv::serve {

namespace {

constexpr const char* kJson = "application/json";

}  // namespace

std::string json_text(const nlohmann::json& j) { return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace); }

void reply(httplib::Response& res, int status, const nlohmann::json& body) {
  res.status = status;
  res.set_content(json_text(body), kJson);
}

// Runs `f`; its failures become the HTTP status and {"error": reason}.
void answer(httplib::Response& res, const std::function<nlohmann::json()>& f) {
  try {
    reply(res, 200, f());
  } catch (const ApiError& e) {
    nlohmann::json body = {{"error", e.what()}};
    if (e.detail().is_object()) body.update(e.detail());
    reply(res, e.status(), body);
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

}  // namespace tnv::serve
