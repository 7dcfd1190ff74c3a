// The tuning page's server without a browser: HTTP requests against the
// emulated node (the real firmware behind the virtual bus): a parameter
// set round-trips, refusals name their reason and change nothing, only
// the tab with control changes anything, the telemetry stream runs at
// the node's rate, and the node thread's queue is bounded.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <future>
#include <thread>

#include "tools/can_emu/node_connection.hpp"
#include "tools/serve/api_error.hpp"
#include "tools/serve/freq_response_for_page.hpp"
#include "tools/serve/tuning_server.hpp"
#include "tests/serve/tuning_server_fixture.hpp"
// Last: <resolv.h>, which it includes, defines the macro _res that Eigen's headers use as a name.
#include <httplib.h>

namespace tnv::serve {
namespace {

using namespace tnv::serve::testing;

TEST_F(TuningServerTest, ServesThePageAndSaysWhichChannelsTheScopeHas) {
  const httplib::Result page = http_->Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("TNV-40 tuning"), std::string::npos);
  const httplib::Result info = http_->Get("/api/info");
  ASSERT_TRUE(info);
  const nlohmann::json j = nlohmann::json::parse(info->body);
  EXPECT_EQ(j["channels"].size(), kScopeChannels.size());
  EXPECT_EQ(j["channels"][0]["name"], "pos_x_mm");
}

TEST_F(TuningServerTest, AParameterSetRoundTrips) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  const httplib::Result r = post("/api/params/set", kTabA, {{"name", "motion.move_ramp_s"}, {"value", "0.25"}});
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(nlohmann::json::parse(r->body)["applied"][0]["text"], "0.25");
  EXPECT_NEAR(param("motion.move_ramp_s")["value"].get<double>(), 0.25, 1e-7) << "the node did not keep the value";
}

TEST_F(TuningServerTest, AnOutOfRangeValueIsRefusedWithItsReasonAndChangesNothing) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  const double before = param("motion.move_ramp_s")["value"].get<double>();
  const httplib::Result r = post("/api/params/set", kTabA, {{"name", "motion.move_ramp_s"}, {"value", 50}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, kHttpBadRequest);
  EXPECT_NE(error_of(r).find("motion.move_ramp_s"), std::string::npos) << error_of(r);
  EXPECT_NE(error_of(r).find("10"), std::string::npos) << "the reason does not give the range: " << error_of(r);
  EXPECT_EQ(param("motion.move_ramp_s")["value"].get<double>(), before);
}

TEST_F(TuningServerTest, TheNodesRefusalOfASafetyParameterNamesTheReason) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  const double before = param("x.limits.following_floor_mm")["value"].get<double>();
  const httplib::Result r =
      post("/api/params/set", kTabA, {{"name", "x.limits.following_floor_mm"}, {"value", before * 0.5}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, kHttpConflict) << r->body;
  EXPECT_NE(error_of(r).find("safety parameter"), std::string::npos) << error_of(r);
  EXPECT_NE(error_of(r).find("commissioning"), std::string::npos) << error_of(r);
  EXPECT_EQ(param("x.limits.following_floor_mm")["value"].get<double>(), before);
}

TEST_F(TuningServerTest, StagedChangesShowInTheListAndCommitTogether) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  ASSERT_EQ(post("/api/params/stage", kTabA, {{"name", "motion.move_ramp_s"}, {"value", 0.3}})->status, 200);
  ASSERT_EQ(post("/api/params/stage", kTabA, {{"name", "motion.move_dwell_s"}, {"value", 0.2}})->status, 200);
  EXPECT_EQ(param("motion.move_ramp_s")["staged"], "0.3");
  EXPECT_NE(param("motion.move_ramp_s")["value"].get<double>(), 0.3) << "a staged value applied before the commit";
  EXPECT_EQ(post("/api/params/set", kTabA, {{"name", "motion.circle_ramp_s"}, {"value", 0.5}})->status, kHttpConflict)
      << "a single set went through while a staged set waited";
  const httplib::Result r = post("/api/params/commit", kTabA);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(nlohmann::json::parse(r->body)["applied"].size(), 2u);
  EXPECT_NEAR(param("motion.move_ramp_s")["value"].get<double>(), 0.3, 1e-7);
  EXPECT_NEAR(param("motion.move_dwell_s")["value"].get<double>(), 0.2, 1e-7);
  EXPECT_FALSE(param("motion.move_ramp_s").contains("staged")) << "still shown staged after the commit";
}

TEST_F(TuningServerTest, OnlyTheTabWithControlChangesAnything) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  const httplib::Result taken = post("/api/control/take", kTabB);
  EXPECT_EQ(taken->status, kHttpConflict);
  EXPECT_EQ(error_of(taken), kAnotherBrowserHasControl);
  const double before = param("motion.move_ramp_s")["value"].get<double>();
  const httplib::Result r = post("/api/params/set", kTabB, {{"name", "motion.move_ramp_s"}, {"value", 0.4}});
  EXPECT_EQ(r->status, kHttpForbidden);
  EXPECT_EQ(error_of(r), kAnotherBrowserHasControl);
  EXPECT_EQ(post("/api/motion", kTabB, {{"kind", "stop"}})->status, kHttpForbidden);
  EXPECT_EQ(post("/api/fault/clear", kTabB)->status, kHttpForbidden);
  EXPECT_EQ(param("motion.move_ramp_s")["value"].get<double>(), before) << "a read-only tab changed a parameter";
  // Given back, the other tab takes it.
  ASSERT_EQ(post("/api/control/release", kTabA)->status, 200);
  EXPECT_EQ(post("/api/control/take", kTabB)->status, 200);
  EXPECT_EQ(post("/api/params/set", kTabA, {{"name", "motion.move_ramp_s"}, {"value", 0.4}})->status, kHttpForbidden);
}

TEST_F(TuningServerTest, ReleasingControlGivesTheNodeBackToOtherHosts) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  ASSERT_EQ(post("/api/params/set", kTabA, {{"name", "motion.move_ramp_s"}, {"value", 0.3}})->status, 200);
  const auto owner = [&] {
    const nlohmann::json status = nlohmann::json::parse(http_->Get("/api/status")->body);
    return status["heartbeat"].is_null() ? -1 : status["heartbeat"]["owner"].get<int>();
  };
  const auto wait_owner = [&](int expected) {
    for (int i = 0; i < 100 && owner() != expected; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    return owner();
  };
  EXPECT_EQ(wait_owner(1), 1) << "the server (host 1) did not take command ownership for the set";
  ASSERT_EQ(post("/api/control/release", kTabA)->status, 200);
  EXPECT_EQ(wait_owner(0), 0) << "the node still belongs to the server after the page released control";
}

// Behaviour, not the machine's speed: the stream carries every sample the
// node sent, once and in order, at the node's own 10 ms spacing (its clock,
// not the wall's), and the table moves in it. The wall clock only bounds
// how long a slow machine may take to deliver 1.5 s of node time.
TEST_F(TuningServerTest, TheTelemetryStreamCarriesEverySampleAtTheNodesSpacingAndTheTableMoves) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  const httplib::Result moved = post("/api/motion", kTabA, {{"kind", "move"}, {"axis", "x"}, {"distance_mm", 2.0},
                                                           {"speed_mm_s", 10.0}});
  ASSERT_EQ(moved->status, 200) << moved->body;
  constexpr double kNodeSpanS = 1.5;
  constexpr double kPeriodS = 0.010;  // tlm.position_ms's default, on the bus's clock
  int events = 0;
  std::vector<double> t_s;
  std::vector<double> pos_x;
  std::string buffer;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  http_->Get(("/api/telemetry?token=" + kTabA).c_str(), [&](const char* data, std::size_t n) {
    buffer.append(data, n);
    for (std::size_t end; (end = buffer.find("\n\n")) != std::string::npos; buffer.erase(0, end + 2)) {
      const nlohmann::json ev = nlohmann::json::parse(buffer.substr(6, end - 6));  // after "data: "
      ++events;
      for (const nlohmann::json& t : ev["t"]) t_s.push_back(t.get<double>());
      for (const nlohmann::json& v : ev["v"])
        if (!v[0].is_null()) pos_x.push_back(v[0].get<double>());
    }
    const bool enough = !t_s.empty() && t_s.back() - t_s.front() >= kNodeSpanS;
    return !enough && std::chrono::steady_clock::now() < deadline;
  });
  ASSERT_GE(t_s.size(), 2u) << "no telemetry within 120 s";
  ASSERT_GE(t_s.back() - t_s.front(), kNodeSpanS) << "the stream carried " << t_s.back() - t_s.front()
                                                  << " s of node time within 120 s of wall time";
  EXPECT_GE(events, 2) << "the history and the samples after it came as one event";
  for (std::size_t i = 1; i < t_s.size(); ++i) {
    // Within 2 ms: a frame's place on the bus varies by a few frame times;
    // a lost sample is 10 ms more, a repeated one 10 ms less.
    ASSERT_NEAR(t_s[i] - t_s[i - 1], kPeriodS, 0.002)
        << "samples " << i - 1 << " and " << i << " (t " << t_s[i - 1] << " s, " << t_s[i]
        << " s): one lost, repeated or out of order";
  }
  ASSERT_FALSE(pos_x.empty());
  EXPECT_GT(pos_x.back() - pos_x.front(), 0.05) << "x did not move in the stream (mm)";
}

class TuningServerNoFrictionTest : public TuningServerTest {
 protected:
  std::string scenario() const override { return TNV_SOURCE_DIR "/tests/data/tables/no-friction.toml"; }
};

TEST_F(TuningServerNoFrictionTest, TheBodeEndpointMeasuresTheOpenLoopWithItsMargins) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  EXPECT_EQ(post("/api/freq-response", kTabA, {{"axis", "w"}})->status, kHttpBadRequest);
  EXPECT_EQ(post("/api/freq-response", kTabA, {{"axis", "x"}, {"loop", "speed"}})->status, kHttpBadRequest);
  // Servo off: the node refuses the experiment, and says why.
  const httplib::Result off = post("/api/freq-response", kTabA, {{"axis", "x"}, {"loop", "open"}});
  ASSERT_TRUE(off);
  EXPECT_EQ(off->status, kHttpConflict) << off->body;
  EXPECT_FALSE(error_of(off).empty());

  ASSERT_EQ(post("/api/motion", kTabA, {{"kind", "enable"}})->status, 200);
  http_->set_read_timeout(240, 0);  // two experiments of 12 s of machine time
  const httplib::Result r = post("/api/freq-response", kTabA, {{"axis", "x"}, {"loop", "open"}});
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const nlohmann::json j = nlohmann::json::parse(r->body);
  ASSERT_GE(j["points"].size(), 10u);
  for (const nlohmann::json& p : j["points"]) {
    EXPECT_TRUE(p["gain_db"].is_number() && p["phase_deg"].is_number() && p["model_gain_db"].is_number());
    EXPECT_GE(p["coherence"].get<double>(), 0.0);
    EXPECT_LE(p["coherence"].get<double>(), 1.0 + 1e-9);
  }
  // The measured crossover and phase margin near the model's (the emulated
  // table's own plant, R-DVSC+DDC at the default 3 mm/s inside its boundary
  // layer: within 7 % there, docs/frequency-response.md).
  const nlohmann::json& m = j["margins"];
  const nlohmann::json& model = j["model_margins"];
  ASSERT_TRUE(m["crossover_hz"].is_number() && model["crossover_hz"].is_number()) << j.dump();
  EXPECT_NEAR(m["crossover_hz"].get<double>(), model["crossover_hz"].get<double>(),
              0.15 * model["crossover_hz"].get<double>());
  EXPECT_NEAR(m["phase_deg"].get<double>(), model["phase_deg"].get<double>(), 0.15 * model["phase_deg"].get<double>());
}

TEST_F(TuningServerTest, ACaptureIsKeptAndDownloadsAsCsv) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  const httplib::Result r = post("/api/captures", kTabA, {{"channels", "pos_x,pos_y"}, {"decimation", 10}, {"duration_s", 0.5}});
  ASSERT_EQ(r->status, 200) << r->body;
  const nlohmann::json taken = nlohmann::json::parse(r->body);
  // 0.5 s every 10 ticks of 1 ms: about 50 samples (the stop lands within a few ms).
  EXPECT_NEAR(taken["samples"].get<double>(), 50.0, 5.0);
  const std::string id = std::to_string(taken["id"].get<int>());
  const httplib::Result csv = http_->Get(("/api/captures/" + id + ".csv").c_str());
  ASSERT_EQ(csv->status, 200);
  EXPECT_EQ(csv->body.rfind("t_s,pos_x_mm,pos_y_mm\n", 0), 0u) << csv->body.substr(0, 80);
  const httplib::Result cols = http_->Get(("/api/captures/" + id).c_str());
  EXPECT_EQ(nlohmann::json::parse(cols->body)["columns"]["pos_x_mm"].size(), taken["samples"].get<std::size_t>());
  EXPECT_EQ(http_->Get("/api/captures/999.csv")->status, kHttpNotFound);
}

TEST(TuningServer, RefusesToStartWithoutThePlottingLibrary) {
  const fs::path empty = temp_dir("no_js");
  can_host::ConnectionOptions c;
  c.emu = true;
  c.emu_storage = (empty / "node.params").string();
  std::vector<std::string> notes;
  auto connection = can_host::NodeConnection::open(c, notes);
  ServeOptions o;
  o.web_dir = TNV_SOURCE_DIR "/tools/serve/web";
  o.js_dir = empty.string();
  TuningServer server(connection->client(), connection->emulated(), o);
  try {
    server.start();
    ADD_FAILURE() << "started without chart.js";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("libjs-chart.js"), std::string::npos) << e.what();
  }
  fs::remove_all(empty);
}

TEST(NodeWorker, AFullQueueIsRefusedAtOnceAndNothingIsQueued) {
  const fs::path dir = temp_dir("queue");
  can_host::ConnectionOptions c;
  c.emu = true;
  c.emu_storage = (dir / "node.params").string();
  std::vector<std::string> notes;
  auto connection = can_host::NodeConnection::open(c, notes);
  ScopeRing ring(16);
  NodeWorker worker(connection->client(), connection->emulated(), ring, 1);
  worker.start();
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::promise<void> running;
  // The first job holds the node thread; the second waits in the queue (its one place).
  auto first = std::async(std::launch::async, [&] {
    return worker.run([&](can_host::NodeClient&) {
      running.set_value();
      released.wait();
      return nlohmann::json(1);
    });
  });
  running.get_future().wait();
  auto second = std::async(std::launch::async, [&] { return worker.run([](can_host::NodeClient&) { return nlohmann::json(2); }); });
  while (worker.pending() < 1) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  try {
    worker.run([](can_host::NodeClient&) { return nlohmann::json(3); });
    ADD_FAILURE() << "a third job was queued past the bound of 1";
  } catch (const ApiError& e) {
    EXPECT_EQ(e.status(), kHttpUnavailable);
  }
  EXPECT_EQ(worker.pending(), 1u);
  release.set_value();
  EXPECT_EQ(first.get(), 1);
  EXPECT_EQ(second.get(), 2);
  worker.stop();
  fs::remove_all(dir);
}

}  // namespace
}  // namespace tnv::serve
