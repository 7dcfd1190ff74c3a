#pragma once
// How the tuning server answers: JSON bodies, and every failure as its
// HTTP status with {"error": reason} (a node's refusal 409 with the
// reason, bad input 400, a silent node or a failing bus 502).
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

namespace httplib {
struct Request;
struct Response;
}  // namespace httplib

namespace tnv::serve {

// The browser tab's token travels in this header.
inline constexpr const char* kTokenHeader = "X-Tnv-Token";

// `j` as one line of JSON. Answers, events and audit lines may quote a
// request's own bytes (a Host, a name): those that are not UTF-8 become
// U+FFFD rather than an exception.
std::string json_text(const nlohmann::json& j);

void reply(httplib::Response& res, int status, const nlohmann::json& body);
// Runs `f` and replies with its JSON; its failures become the HTTP status and {"error": reason}.
void answer(httplib::Response& res, const std::function<nlohmann::json()>& f);
// The request body as a JSON object ({} when empty); ApiError(400) otherwise.
nlohmann::json body_json(const httplib::Request& req);
// A string field of the body; ApiError(400) naming it when missing.
std::string text_field(const nlohmann::json& body, const char* key);

}  // namespace tnv::serve
