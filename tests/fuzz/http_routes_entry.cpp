#include "tests/fuzz/http_routes_entry.hpp"

#include <array>
#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "tools/can_emu/node_connection.hpp"
#include "tools/serve/tuning_server.hpp"
// Last: <resolv.h>, which it includes, defines the macro _res that Eigen's headers use as a name.
#include <httplib.h>

namespace tnv::fuzz {

namespace {

const std::string kHostOwn = "127.0.0.1:8040";
const std::string kTab = "fuzz-tab-0123456789";

struct Route {
  const char* method;  // nullptr: the fuzzed text
  const char* path;    // nullptr: the fuzzed text
};
constexpr std::array<Route, 29> kRoutes{{
    {"GET", "/api/info"},           {"GET", "/api/status"},          {"GET", "/api/control"},
    {"GET", "/api/params"},         {"GET", "/api/captures"},        {"GET", "/api/captures/1"},
    {"GET", "/api/captures/1.csv"}, {"GET", "/api/telemetry"},       {"POST", "/api/control/take"},
    {"POST", "/api/control/release"}, {"POST", "/api/control/heartbeat"}, {"POST", "/api/params/set"},
    {"POST", "/api/params/stage"},  {"POST", "/api/params/commit"},  {"POST", "/api/params/discard"},
    {"POST", "/api/fault/clear"},   {"POST", "/api/motion"},         {"POST", "/api/captures"},
    {"POST", "/api/freq-response"}, {"GET", "/"},                    {"POST", nullptr},
    {"GET", nullptr},               {nullptr, "/api/motion"},        {nullptr, nullptr},
    // The Program panel's (appended: the seeds above keep their routes).
    {"GET", "/api/program"},        {"POST", "/api/program/preview"}, {"POST", "/api/program/run"},
    {"POST", "/api/program/resume"}, {"POST", "/api/program/hold"},
}};

// One server for the whole run: its node thread never runs.
struct Rig {
  std::unique_ptr<can_host::NodeConnection> connection;
  std::unique_ptr<serve::TuningServer> server;
  std::string cookie;  // "name=value" of a session opened with the secret
};

Rig& rig() {
  static Rig* r = [] {
    auto* made = new Rig;
    can_host::ConnectionOptions c;
    c.emu = true;
    std::vector<std::string> notes;
    made->connection = can_host::NodeConnection::open(c, notes);
    serve::ServeOptions o;
    o.audit_path = "/dev/null";
    o.port = 8040;
    // Control changes by request only: with the 0.3 s dead-man, a holder
    // went quiet between two snapshots of one input and its lapse read as
    // the request's doing (the dead-man has its own tests).
    o.control_deadman = std::chrono::hours(24);
    made->server = std::make_unique<serve::TuningServer>(made->connection->client(), made->connection->emulated(), o);
    made->server->worker().stop();  // every node job refused at once (503)
    httplib::Request req;
    req.method = "GET";
    req.path = "/";
    req.set_header("Host", kHostOwn);
    req.params.emplace("token", made->server->secret());
    httplib::Response res;
    made->server->handle(req, res);
    const std::string set = res.get_header_value("Set-Cookie");
    made->cookie = set.substr(0, set.find(';'));
    return made;
  }();
  return *r;
}

// "a=b&c" into params.
void add_query(httplib::Request& req, const std::string& query) {
  std::size_t start = 0;
  while (start <= query.size()) {
    const std::size_t end = std::min(query.find('&', start), query.size());
    const std::string part = query.substr(start, end - start);
    const std::size_t eq = part.find('=');
    req.params.emplace(part.substr(0, eq), eq == std::string::npos ? "" : part.substr(eq + 1));
    start = end + 1;
  }
}

}  // namespace

std::string http_routes(const std::uint8_t* data, std::size_t size) {
  Rig& r = rig();
  const std::uint8_t b0 = size > 0 ? data[0] : 0;
  const std::uint8_t b1 = size > 1 ? data[1] : 0;
  const std::string rest = size > 2 ? std::string(reinterpret_cast<const char*>(data) + 2, size - 2) : "";
  const std::size_t nl = rest.find('\n');
  const std::string text = nl == std::string::npos ? "" : rest.substr(0, nl);
  const std::string body = nl == std::string::npos ? rest : rest.substr(nl + 1);

  httplib::Request req;
  const Route route = kRoutes[(b1 & 0x1F) % kRoutes.size()];
  req.method = route.method != nullptr ? route.method : text.substr(0, 8);
  std::string target = route.path != nullptr ? route.path : text;
  if (target == "/" && route.method != nullptr) target = "/?token=" + (b0 & 1 ? text : r.server->secret());
  const std::size_t q = target.find('?');
  req.path = target.substr(0, q);
  if (q != std::string::npos) add_query(req, target.substr(q + 1));
  if (req.path == "/api/params" || req.path == "/api/telemetry") add_query(req, "filter=motion&token=" + kTab);

  const int host_sel = b0 & 7;
  const std::string host = host_sel == 0 ? kHostOwn
                           : host_sel == 1 ? "localhost:8040"
                           : host_sel == 2 ? "[::1]:8040"
                           : host_sel == 3 ? "attacker.example:8040"
                                           : text;
  if (host_sel != 4) req.set_header("Host", host);
  const int origin_sel = (b0 >> 3) & 7;
  if (origin_sel == 1) req.set_header("Origin", "http://attacker.example:8040");
  else if (origin_sel == 2) req.set_header("Origin", "null");
  else if (origin_sel == 4) req.set_header("Origin", text);
  else if (origin_sel != 3) req.set_header("Origin", "http://" + host);
  const int auth_sel = b0 >> 6;
  if (auth_sel == 0) req.set_header("Authorization", "Bearer " + r.server->secret());
  else if (auth_sel == 1) req.set_header("Cookie", r.cookie);
  else if (auth_sel == 2) req.set_header("Authorization", "Bearer " + text);
  const int type_sel = (b1 >> 5) & 3;
  req.set_header("Content-Type", type_sel == 0   ? "application/json"
                                 : type_sel == 1 ? "application/json; charset=utf-8"
                                 : type_sel == 2 ? "text/plain"
                                                 : text);
  req.set_header("X-Tnv-Token", (b1 & 0x80) ? text : kTab);
  req.body = body;

  const nlohmann::json before = r.server->state_snapshot();
  httplib::Response res;
  const serve::GateVerdict verdict = r.server->handle(req, res);
  const nlohmann::json after = r.server->state_snapshot();

  if (res.status < 100 || res.status > 599) return "status " + std::to_string(res.status);
  if (!verdict.ok()) {
    if (res.status != verdict.status) return "the gate refused with " + std::to_string(verdict.status) +
                                             " but the answer was " + std::to_string(res.status);
    if (after != before) return "a request the gate refused changed " + before.dump() + " to " + after.dump();
  }
  if (res.status >= 400 && res.status < 500 && after != before)
    return "a " + std::to_string(res.status) + " answer changed " + before.dump() + " to " + after.dump();
  if (host_sel == 3 && res.status != 403) return "a foreign Host was answered " + std::to_string(res.status);
  const bool api = req.path.rfind("/api/", 0) == 0;
  if (api && auth_sel >= 2 && res.status < 300 && verdict.session.empty())
    return "an API route answered " + std::to_string(res.status) + " without credentials";
  if (res.status >= 400 && res.get_header_value("Content-Type") == "application/json") {
    const nlohmann::json j = nlohmann::json::parse(res.body, nullptr, false);
    if (j.is_discarded() || !j.contains("error") || !j["error"].is_string())
      return "a JSON error answer without its reason: " + res.body.substr(0, 80);
  }
  return "";
}

}  // namespace tnv::fuzz
