// Who may use the tuning page's server, over real HTTP on the loopback
// against the emulated node: without the secret every API route and the
// telemetry stream answer 401, a foreign Host 403 whatever the secret, a
// command without the page's Origin 403, a body that is not JSON 415 and
// an oversized one 413 — and none of them changes anything. The printed
// URL's secret becomes an HttpOnly, SameSite=Strict cookie; every
// state-changing request is in the audit trail; a tab that stops its
// heartbeat loses control and its move stops within 0.5 s of machine time.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <chrono>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "tests/serve/tuning_server_fixture.hpp"
#include "tools/serve/api_error.hpp"
// Last: <resolv.h>, which it includes, defines the macro _res that Eigen's headers use as a name.
#include <httplib.h>

namespace tnv::serve {
namespace {

using namespace tnv::serve::testing;

// A client with no default headers: every header is the test's.
class PageAccessTest : public TuningServerTest {
 protected:
  httplib::Result raw(const std::string& method, const std::string& path, const httplib::Headers& headers,
                      const std::string& body = "", const std::string& type = "application/json") {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(10, 0);
    if (method == "GET") return c.Get(path.c_str(), headers);
    return c.Post(path.c_str(), headers, body, type.c_str());
  }
  httplib::Headers bearer() const { return {{"Authorization", "Bearer " + server_->secret()}}; }
  httplib::Headers command(const std::string& origin_value) const {
    return {{"Authorization", "Bearer " + server_->secret()}, {"Origin", origin_value}, {"X-Tnv-Token", kTabA}};
  }
};

TEST_F(PageAccessTest, WithoutTheSecretEveryApiRouteAndTheStreamAre401AndNothingChanges) {
  const nlohmann::json before = server_->state_snapshot();
  for (const char* path : {"/api/info", "/api/status", "/api/params", "/api/control", "/api/captures",
                           "/api/telemetry?token=tab-a-0123456789"}) {
    const httplib::Result r = raw("GET", path, {});
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 401) << path;
  }
  const httplib::Headers guessed = {{"Origin", origin()}, {"X-Tnv-Token", kTabA},
                                    {"Authorization", "Bearer " + std::string(64, '0')}};
  for (const httplib::Headers& h : {httplib::Headers{{"Origin", origin()}, {"X-Tnv-Token", kTabA}}, guessed}) {
    EXPECT_EQ(raw("POST", "/api/control/take", h)->status, 401);
    EXPECT_EQ(raw("POST", "/api/motion", h, R"({"kind":"enable"})")->status, 401);
    EXPECT_EQ(raw("POST", "/api/params/set", h, R"({"name":"motion.move_ramp_s","value":0.3})")->status, 401);
  }
  EXPECT_EQ(server_->state_snapshot(), before) << "a request without the secret changed the server's state";
  // The page's own files carry no secret: served, so the page can say what is missing.
  EXPECT_EQ(raw("GET", "/", {})->status, 200);
}

TEST_F(PageAccessTest, AForeignHostIs403WhateverTheSecret) {
  const nlohmann::json before = server_->state_snapshot();
  const std::string foreign = "attacker.example:" + std::to_string(port_);
  httplib::Headers h = command("http://" + foreign);
  h.emplace("Host", foreign);
  for (const char* path : {"/", "/api/info"}) EXPECT_EQ(raw("GET", path, h)->status, 403) << path;
  const httplib::Result r = raw("POST", "/api/control/take", h);
  EXPECT_EQ(r->status, 403);
  EXPECT_NE(error_of(r).find("attacker.example"), std::string::npos) << error_of(r);
  EXPECT_EQ(server_->state_snapshot(), before);
  // The loopback under its other names is this server.
  httplib::Headers local = bearer();
  local.emplace("Host", "localhost:" + std::to_string(port_));
  EXPECT_EQ(raw("GET", "/api/info", local)->status, 200);
}

// Found by the http_routes fuzz target: the refusal quoted the Host's bytes,
// and a byte that is not UTF-8 made the JSON answer throw instead of being sent.
TEST_F(PageAccessTest, AHostThatIsNotUtf8IsRefusedWithAReadableAnswer) {
  const nlohmann::json before = server_->state_snapshot();
  httplib::Headers h = bearer();
  h.emplace("Host", "\xff\xfe:" + std::to_string(port_));
  const httplib::Result r = raw("POST", "/api/control/take", h);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  EXPECT_FALSE(nlohmann::json::parse(r->body, nullptr, false).is_discarded()) << r->body;
  EXPECT_FALSE(error_of(r).empty());
  EXPECT_EQ(server_->state_snapshot(), before);
}

TEST_F(PageAccessTest, ACommandWithoutThePagesOriginIs403AndChangesNothing) {
  const double ramp = param("motion.move_ramp_s")["value"].get<double>();
  const nlohmann::json before = server_->state_snapshot();
  httplib::Headers no_origin = bearer();
  no_origin.emplace("X-Tnv-Token", kTabA);
  for (const httplib::Headers& h : {command("http://attacker.example:" + std::to_string(port_)), command("null"),
                                    command("http://127.0.0.1:1"), no_origin}) {
    EXPECT_EQ(raw("POST", "/api/control/take", h)->status, 403);
    EXPECT_EQ(raw("POST", "/api/motion", h, R"({"kind":"enable"})")->status, 403);
    EXPECT_EQ(raw("POST", "/api/params/set", h, R"({"name":"motion.move_ramp_s","value":0.3})")->status, 403);
  }
  EXPECT_EQ(server_->state_snapshot(), before);  // before param(): its read is a job for the node thread
  EXPECT_EQ(param("motion.move_ramp_s")["value"].get<double>(), ramp);
  // With the page's origin the same request is the operator's.
  EXPECT_EQ(raw("POST", "/api/control/take", command(origin()))->status, 200);
}

TEST_F(PageAccessTest, ABodyThatIsNotJsonIs415AndAnOversizedOne413) {
  ASSERT_EQ(raw("POST", "/api/control/take", command(origin()))->status, 200);
  const std::size_t jobs = server_->worker().jobs_offered();
  EXPECT_EQ(raw("POST", "/api/params/set", command(origin()), "name=motion.move_ramp_s&value=0.3",
                "application/x-www-form-urlencoded")->status, 415);
  EXPECT_EQ(raw("POST", "/api/motion", command(origin()), R"({"kind":"enable"})", "text/plain")->status, 415);
  const std::string big = R"({"name":"motion.move_ramp_s","value":0.3,"pad":")" + std::string(70'000, 'x') + "\"}";
  EXPECT_EQ(raw("POST", "/api/params/set", command(origin()), big)->status, 413);
  EXPECT_EQ(server_->worker().jobs_offered(), jobs) << "a refused body reached the node thread";
}

TEST_F(PageAccessTest, ThePrintedUrlsSecretBecomesAnHttpOnlyStrictCookie) {
  const std::string url = server_->page_url("127.0.0.1", port_);
  const std::string path = url.substr(url.find("/?token="));
  httplib::Client c("127.0.0.1", port_);
  const httplib::Result wrong = c.Get(("/?token=" + std::string(64, 'a')).c_str());
  EXPECT_EQ(wrong->status, 401);
  EXPECT_FALSE(wrong->has_header("Set-Cookie"));
  const httplib::Result r = c.Get(path.c_str());
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 303);
  EXPECT_EQ(r->get_header_value("Location"), "/") << "the secret stays in the address bar";
  const std::string cookie = r->get_header_value("Set-Cookie");
  EXPECT_NE(cookie.find("HttpOnly"), std::string::npos) << cookie;
  EXPECT_NE(cookie.find("SameSite=Strict"), std::string::npos) << cookie;
  EXPECT_EQ(cookie.find(server_->secret()), std::string::npos) << "the cookie is the secret itself";
  const std::string pair = cookie.substr(0, cookie.find(';'));
  EXPECT_EQ(raw("GET", "/api/info", {{"Cookie", pair}})->status, 200);
  EXPECT_EQ(raw("GET", "/api/info", {{"Cookie", pair + "x"}})->status, 401);
  httplib::Headers h = {{"Cookie", "other=1; " + pair}, {"Origin", origin()}, {"X-Tnv-Token", kTabA}};
  EXPECT_EQ(raw("POST", "/api/control/take", h)->status, 200);
}

TEST_F(PageAccessTest, EveryStateChangingRequestIsInTheAuditTrail) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  ASSERT_EQ(post("/api/params/set", kTabA, {{"name", "motion.move_ramp_s"}, {"value", 0.3}})->status, 200);
  EXPECT_EQ(raw("POST", "/api/motion", command("http://attacker.example"), R"({"kind":"enable"})")->status, 403);
  EXPECT_EQ(raw("POST", "/api/motion", {{"Origin", origin()}}, R"({"kind":"enable"})")->status, 401);
  const std::vector<nlohmann::json> lines = audit_lines();
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0]["path"], "/api/control/take");
  EXPECT_EQ(lines[0]["session"], "bearer");
  EXPECT_EQ(lines[0]["tab"], kTabA);
  EXPECT_EQ(lines[1]["body"]["name"], "motion.move_ramp_s");
  EXPECT_EQ(lines[1]["status"], 200);
  EXPECT_EQ(lines[1]["answer"]["applied"][0]["text"], "0.3") << lines[1].dump();
  EXPECT_EQ(lines[2]["status"], 403);
  EXPECT_NE(lines[2]["answer"]["error"].get<std::string>().find("Origin"), std::string::npos);
  EXPECT_EQ(lines[3]["status"], 401);
  EXPECT_TRUE(lines[3]["session"].is_null());
  for (const nlohmann::json& l : lines) EXPECT_TRUE(l.contains("time") && l.contains("peer")) << l.dump();
}

class ReadOnlyServerTest : public PageAccessTest {
 protected:
  void adjust(ServeOptions& o) const override { o.read_only = true; }
};

TEST_F(ReadOnlyServerTest, WatchesButEveryStateChangingRouteIs403) {
  EXPECT_EQ(raw("GET", "/api/status", bearer())->status, 200);
  EXPECT_EQ(raw("GET", "/api/params?filter=motion.move_ramp_s", bearer())->status, 200);
  const nlohmann::json before = server_->state_snapshot();
  for (const char* path : {"/api/control/take", "/api/control/release", "/api/control/heartbeat", "/api/motion",
                           "/api/params/set", "/api/params/stage", "/api/params/commit", "/api/params/discard",
                           "/api/fault/clear", "/api/captures", "/api/freq-response"}) {
    const httplib::Result r = raw("POST", path, command(origin()), "{}");
    EXPECT_EQ(r->status, 403) << path;
    EXPECT_NE(error_of(r).find("read-only"), std::string::npos) << path << ": " << error_of(r);
  }
  EXPECT_EQ(server_->state_snapshot(), before);
}

class DeadmanTest : public PageAccessTest {
 protected:
  std::chrono::milliseconds deadman() const override { return std::chrono::milliseconds(300); }
};

// A tab that takes control, starts a 50 mm move at 10 mm/s, sends its
// heartbeat until the table has moved 1 mm, then goes silent: the move
// must come to rest (within 10 um of where it ends) within 0.5 s of
// machine time of the newest sample seen at the silence (an upper bound:
// the last heartbeat went out after it).
TEST_F(DeadmanTest, AMoveStopsWithinHalfASecondOfTheLastHeartbeat) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  ASSERT_EQ(post("/api/motion", kTabA, {{"kind", "enable"}})->status, 200);
  ASSERT_EQ(post("/api/motion", kTabA, {{"kind", "move"}, {"axis", "x"}, {"distance_mm", 50.0}, {"speed_mm_s", 10.0}})
                ->status,
            200);
  std::atomic<bool> silent{false};
  std::atomic<bool> refused{false};
  std::thread heart([&] {
    httplib::Client c("127.0.0.1", port_);
    c.set_default_headers({{"Authorization", "Bearer " + server_->secret()}, {"Origin", origin()}, {"X-Tnv-Token", kTabA}});
    while (!silent) {
      const httplib::Result r = c.Post("/api/control/heartbeat", "", "application/json");
      if (!r || r->status != 200) refused = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  double x0 = NAN, t_silent = NAN, x_last = NAN, t_latest = 0.0;
  std::vector<std::pair<double, double>> after;  // (t, x) from the silence on
  std::string buffer;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  http_->Get(("/api/telemetry?token=" + kTabA).c_str(), [&](const char* data, std::size_t n) {
    buffer.append(data, n);
    for (std::size_t end; (end = buffer.find("\n\n")) != std::string::npos; buffer.erase(0, end + 2)) {
      const nlohmann::json ev = nlohmann::json::parse(buffer.substr(6, end - 6));
      for (std::size_t i = 0; i < ev["t"].size(); ++i) {
        if (ev["v"][i][0].is_null()) continue;
        const double t = ev["t"][i].get<double>(), x = ev["v"][i][0].get<double>();
        if (std::isnan(x0)) x0 = x;
        if (silent) after.emplace_back(t, x);
        x_last = x;
        t_latest = t;
      }
    }
    if (!silent && !std::isnan(x0) && x_last - x0 >= 1.0) {
      t_silent = t_latest;
      silent = true;
    }
    // Done 1.5 s of machine time after the silence, or at the wall deadline.
    return !(silent && t_latest > t_silent + 1.5) && std::chrono::steady_clock::now() < deadline;
  });
  silent = true;
  heart.join();
  EXPECT_FALSE(refused) << "a heartbeat was refused while the tab still sent them";
  ASSERT_FALSE(std::isnan(t_silent)) << "the table never moved 1 mm";
  ASSERT_GT(t_latest, t_silent + 1.5) << "the stream ended before 1.5 s of machine time after the silence";
  // At rest: within 10 um of where the table ended (an encoder count is 0.4 um; the servo holds).
  double t_moved = t_silent;
  for (const auto& [t, x] : after)
    if (std::fabs(x - x_last) > 0.01) t_moved = std::max(t_moved, t);
  EXPECT_LE(t_moved - t_silent, 0.5) << "the table still moved " << t_moved - t_silent
                                     << " s of machine time after the tab went silent";
  EXPECT_LT(x_last - x0, 10.0) << "the move ran on (mm)";
  RecordProperty("stopped_after_silence_s", std::to_string(t_moved - t_silent));
  std::printf("dead-man: the move stopped %.3f s of machine time after the silence (x moved %.2f mm)\n",
              t_moved - t_silent, x_last - x0);
  EXPECT_FALSE(server_->state_snapshot()["control_taken"].get<bool>()) << "the silent tab kept control";
  const std::vector<nlohmann::json> lines = audit_lines();
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines.back()["event"], "dead-man") << lines.back().dump();
  EXPECT_NE(lines.back()["detail"].get<std::string>().find("motion stopped"), std::string::npos) << lines.back().dump();
}

}  // namespace
}  // namespace tnv::serve
