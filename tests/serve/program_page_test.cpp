// The Program panel's server side, over real HTTP on the loopback against
// the emulated node: a preview of a small program (its pieces, points and
// lines, an arc drawn in chords on its circle), a huge one thinned and
// saying so, a refused program (400 naming line and column, nothing sent:
// the servo stays off), a run refused without control, a run to its end
// (its line advancing, the audit trail with the program's size, lines and
// SHA-256 and not its text), a Stop and the dead-man rule interrupting a
// running program, and the program route's own body limit.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>
#include <thread>
#include <utility>

#include "tests/serve/tuning_server_fixture.hpp"
#include "tools/gcode/gcode_program.hpp"
#include "tools/serve/page_program.hpp"
#include "tools/serve/program_state.hpp"
// Last: <resolv.h>, which it includes, defines the macro _res that Eigen's headers use as a name.
#include <httplib.h>

namespace tnv::serve {
namespace {

using namespace tnv::serve::testing;

// Incremental (the table starts where the scenario's circle does): lines 2 and 3
// are lines, line 4 a half circle about start + (2.5, 2.5) back to the start.
const std::string kSquareAndArc = "G21 G91 G17\nG1 X5 Y0 F600\nG1 X0 Y5\nG2 X-5 Y-5 I-2.5 J-2.5\nM2\n";
// 2 mm and 1 mm at 10 mm/s: 0.3 s of machine time.
const std::string kShort = "G21 G91 G17\nG1 X2 Y0 F600\nG1 X0 Y1\nM2\n";
const std::string kShortSha256 = "1200ab278c3ad0d28edf250de0e5a47625f8fe632c916f20c66dbb11a23031e0";  // sha256sum of kShort
// 100 elements of 1 mm at 5 mm/s: 20 s of machine time, long enough to be stopped halfway whatever the load.
const std::string kLong = [] {
  std::string text = "G21 G91 G17 F300\n";
  for (int i = 0; i < 100; ++i) text += "G1 X1\n";
  return text;
}();

class ProgramPageTest : public TuningServerTest {
 protected:
  // A run of 20 s of machine time may take longer on a loaded machine: control must outlast it
  // (these tests send no heartbeat; ProgramDeadmanTest does).
  std::chrono::milliseconds deadman() const override { return std::chrono::minutes(5); }
  nlohmann::json program() {
    const httplib::Result r = http_->Get("/api/program");
    EXPECT_TRUE(r && r->status == 200);
    return r ? nlohmann::json::parse(r->body) : nlohmann::json();
  }
  // The node's state from its heartbeat (waiting for the first one).
  std::string node_state() {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    for (;;) {
      const httplib::Result r = http_->Get("/api/status");
      const nlohmann::json s = nlohmann::json::parse(r->body);
      if (!s["heartbeat"].is_null()) return s["heartbeat"]["state"].get<std::string>();
      if (std::chrono::steady_clock::now() > deadline) return "no heartbeat";
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  // Polls the run until `done` holds; a generous wall deadline for a busy machine (never a measurement).
  template <typename F>
  nlohmann::json wait_program(F done, const char* what) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    for (;;) {
      nlohmann::json p = program();
      if (done(p)) return p;
      if (std::chrono::steady_clock::now() > deadline) {
        ADD_FAILURE() << what << " not seen within 60 s: " << p.dump();
        return p;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  void run_until_halfway_started() {
    const httplib::Result run = post("/api/program/run", kTabA, {{"gcode", kLong}});
    ASSERT_TRUE(run);
    ASSERT_EQ(run->status, 200) << run->body;
    EXPECT_TRUE(nlohmann::json::parse(run->body).value("started", false)) << run->body;
    wait_program([](const nlohmann::json& p) { return p["phase"] == "running" && p["fraction"].get<double>() >= 0.02; },
                 "the long program running (2 of its 100 mm run)");
  }
};

TEST_F(ProgramPageTest, APreviewHasEachSegmentsPiecesPointsAndLines) {
  const httplib::Result r = post("/api/program/preview", kTabA, {{"gcode", kSquareAndArc}});
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const nlohmann::json p = nlohmann::json::parse(r->body);
  EXPECT_EQ(p["segments"], 3);
  EXPECT_GE(p["lines"].get<int>(), 4);
  EXPECT_FALSE(p["thinned"].get<bool>());
  const double semicircle_mm = std::numbers::pi * std::sqrt(2.0 * 2.5 * 2.5);
  EXPECT_NEAR(p["length_mm"].get<double>(), 10.0 + semicircle_mm, 1e-6);
  EXPECT_NEAR(p["cycle_time_s"].get<double>(), (10.0 + semicircle_mm) / 10.0, 1e-6);
  ASSERT_EQ(p["pieces"].size(), 3U);
  const nlohmann::json& pieces = p["pieces"];
  EXPECT_EQ(pieces[0]["line"], 2);
  EXPECT_EQ(pieces[1]["line"], 3);
  EXPECT_EQ(pieces[2]["line"], 4);
  // The table stands where the node says, and the first piece starts there.
  const double x0 = p["start"][0].get<double>(), y0 = p["start"][1].get<double>();
  EXPECT_EQ(pieces[0]["points"].size(), 4U);
  EXPECT_NEAR(pieces[0]["points"][0].get<double>(), x0, 1e-4);
  EXPECT_NEAR(pieces[0]["points"][1].get<double>(), y0, 1e-4);
  ASSERT_EQ(pieces[1]["points"].size(), 4U);
  EXPECT_NEAR(pieces[1]["points"][0].get<double>(), x0 + 5.0, 1e-4);
  EXPECT_NEAR(pieces[1]["points"][3].get<double>(), y0 + 5.0, 1e-4);
  // The half circle in 5-degree chords: 36 chords, 37 points, every one on the circle.
  const nlohmann::json& arc = pieces[2]["points"];
  ASSERT_EQ(arc.size(), 2U * 37U);
  for (std::size_t i = 0; i < arc.size(); i += 2)
    EXPECT_NEAR(std::hypot(arc[i].get<double>() - x0 - 2.5, arc[i + 1].get<double>() - y0 - 2.5), std::sqrt(12.5), 1e-3)
        << i;
  EXPECT_NEAR(arc[arc.size() - 2].get<double>(), x0, 1e-4) << "the half circle ends at the start";
  EXPECT_EQ(p["points"], 2 + 2 + 37);
  EXPECT_LT(p["travel"]["x"][0].get<double>(), p["travel"]["x"][1].get<double>());
  EXPECT_EQ(program()["phase"], "idle") << "a preview runs nothing";
  EXPECT_EQ(node_state(), "disabled");
}

TEST(ProgramPreview, AHugePathIsThinnedWithinItsBudgetAndSaysSo) {
  std::string text = "G21 G90 G17 F100\n";
  for (int i = 1; i <= 3000; ++i) text += "G1 X" + std::to_string(i * 0.01) + " Y" + std::to_string(i % 2 * 0.5) + "\n";
  can_host::ProgramPlan plan;
  plan.parsed = gcode::parse_gcode(text);
  ASSERT_FALSE(plan.parsed.error) << gcode::to_string(*plan.parsed.error);
  const nlohmann::json p = preview_json(plan, 600);
  EXPECT_TRUE(p["thinned"].get<bool>());
  EXPECT_NE(p["note"], "");
  EXPECT_LE(p["points"].get<std::size_t>(), 600U);
  EXPECT_GT(p["points"].get<std::size_t>(), 100U);
  const nlohmann::json& first = p["pieces"].front();
  const nlohmann::json& last = p["pieces"].back();
  EXPECT_EQ(first["line"], 2);
  EXPECT_EQ(last["last_line"], 3001);
  EXPECT_EQ(first["points"][0], 0.0);
  EXPECT_NEAR(last["points"][last["points"].size() - 2].get<double>(), 30.0, 1e-9) << "the path's end is kept";
  EXPECT_EQ(p["segments"], 3000);
}

TEST_F(ProgramPageTest, ARefusedProgramIs400NamingLineAndColumnAndSendsNothing) {
  const std::string bad = "G21 G91\nG1 X5 F600\nG1 X20 E3\n";  // line 3, column 8: unsupported word E
  const httplib::Result preview = post("/api/program/preview", kTabA, {{"gcode", bad}});
  ASSERT_TRUE(preview);
  EXPECT_EQ(preview->status, 400);
  const nlohmann::json e = nlohmann::json::parse(preview->body);
  EXPECT_EQ(e["line"], 3) << preview->body;
  EXPECT_EQ(e["column"], 8) << preview->body;
  EXPECT_NE(e["error"].get<std::string>().find("line 3"), std::string::npos) << preview->body;

  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  const httplib::Result run = post("/api/program/run", kTabA, {{"gcode", bad}});
  ASSERT_TRUE(run);
  EXPECT_EQ(run->status, 400) << run->body;
  EXPECT_EQ(nlohmann::json::parse(run->body)["line"], 3) << run->body;
  const nlohmann::json p = program();
  EXPECT_EQ(p["phase"], "ended");
  EXPECT_EQ(p["end"], "refused");
  EXPECT_EQ(node_state(), "disabled") << "the servo was switched on for a refused program";
}

TEST_F(ProgramPageTest, OnlyTheTabWithControlRuns) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  const std::size_t offered = server_->worker().jobs_offered();
  const httplib::Result run = post("/api/program/run", kTabB, {{"gcode", kShort}});
  ASSERT_TRUE(run);
  EXPECT_EQ(run->status, 403) << run->body;
  EXPECT_EQ(server_->worker().jobs_offered(), offered);
  EXPECT_EQ(program()["phase"], "idle");
  EXPECT_EQ(node_state(), "disabled");
}

TEST_F(ProgramPageTest, AProgramRunsToItsEndAndTheAuditTrailNamesItsDigest) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  const httplib::Result run = post("/api/program/run", kTabA, {{"gcode", kShort}});
  ASSERT_TRUE(run);
  ASSERT_EQ(run->status, 200) << run->body;
  const nlohmann::json p = wait_program([](const nlohmann::json& s) { return s["phase"] == "ended"; }, "the run's end");
  EXPECT_EQ(p["end"], "done") << p.dump();
  EXPECT_EQ(p["line"], 3) << "the last line the node ran";
  EXPECT_EQ(p["element"], 2);
  EXPECT_NEAR(p["fraction"].get<double>(), 1.0, 1e-9);
  bool logged = false;
  for (const nlohmann::json& line : audit_lines()) {
    if (line.value("path", "") != "/api/program/run") continue;
    logged = true;
    EXPECT_EQ(line["body"]["gcode"]["sha256"], kShortSha256);
    EXPECT_EQ(line["body"]["gcode"]["bytes"], kShort.size());
    EXPECT_EQ(line["body"]["gcode"]["lines"], 4);
    EXPECT_EQ(line.dump().find("X2 Y1"), std::string::npos) << "the program's text is in the trail";
  }
  EXPECT_TRUE(logged);
}

// A program pause waits for the Resume of the tab with control: another
// tab is refused (403), nothing paused is 409, and the Resume is in the
// audit trail.
TEST_F(ProgramPageTest, APauseWaitsForTheResumeOfTheTabWithControl) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  const httplib::Result early = post("/api/program/resume", kTabA);
  ASSERT_TRUE(early);
  EXPECT_EQ(early->status, 409) << "nothing is paused: " << early->body;
  const httplib::Result run = post("/api/program/run", kTabA, {{"gcode", "G21 G91 G17\nG1 X1 F600\nM0\nG1 X-1\nM2\n"}});
  ASSERT_TRUE(run);
  ASSERT_EQ(run->status, 200) << run->body;
  const nlohmann::json paused =
      wait_program([](const nlohmann::json& s) { return !s["pause"].is_null() || s["phase"] == "ended"; }, "the pause");
  ASSERT_FALSE(paused["pause"].is_null()) << paused.dump();
  EXPECT_EQ(paused["pause"]["line"], 3);
  EXPECT_EQ(paused["pause"]["reason"], "program stop (M0)");
  EXPECT_EQ(paused["phase"], "running");
  const httplib::Result other = post("/api/program/resume", kTabB);
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 403) << other->body;
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_FALSE(program()["pause"].is_null()) << "it went on without the Resume";
  const httplib::Result resume = post("/api/program/resume", kTabA);
  ASSERT_TRUE(resume);
  EXPECT_EQ(resume->status, 200) << resume->body;
  const nlohmann::json p = wait_program([](const nlohmann::json& s) { return s["phase"] == "ended"; }, "the run's end");
  EXPECT_EQ(p["end"], "done") << p.dump();
  EXPECT_TRUE(p["pause"].is_null());
  int resumes_logged = 0;
  for (const nlohmann::json& line : audit_lines())
    if (line.value("path", "") == "/api/program/resume") ++resumes_logged;
  EXPECT_EQ(resumes_logged, 3) << "the early one, the other tab's and the accepted one";
}

// Run from line on the page: the same interpreter as tnvctl run --from-line.
// From line 3 of the square and arc, the preview has no piece of line 2 (the
// approach to line 3's start is a rapid) and ends where the whole program's does; the run ends there too, the lines it
// reports never below 3.
TEST_F(ProgramPageTest, ARunFromLineStartsThereAndEndsWhereTheWholeProgramEnds) {
  const httplib::Result whole = post("/api/program/preview", kTabA, {{"gcode", kSquareAndArc}});
  ASSERT_TRUE(whole);
  ASSERT_EQ(whole->status, 200) << whole->body;
  // The clearance at the bottom of Z's travel: the retract never goes down, so the head stays where it
  // stands and only the XY approach differs from the whole run.
  const httplib::Result from = post("/api/program/preview", kTabA,
                                    {{"gcode", kSquareAndArc}, {"from_line", 3}, {"clearance_z_mm", -300.0}});
  ASSERT_TRUE(from);
  ASSERT_EQ(from->status, 200) << from->body;
  const nlohmann::json w = nlohmann::json::parse(whole->body);
  const nlohmann::json f = nlohmann::json::parse(from->body);
  for (const nlohmann::json& piece : f["pieces"]) EXPECT_GE(piece["line"].get<int>(), 3) << f.dump();
  const nlohmann::json& w_end = w["pieces"].back()["points"];
  const nlohmann::json& f_end = f["pieces"].back()["points"];
  EXPECT_NEAR(f_end[f_end.size() - 2].get<double>(), w_end[w_end.size() - 2].get<double>(), 1e-4);
  EXPECT_NEAR(f_end.back().get<double>(), w_end.back().get<double>(), 1e-4);
  // The approach covers line 2's 5 mm at rapid (50 mm/s), not at line 2's 10 mm/s: 0.4 s less.
  EXPECT_NEAR(f["cycle_time_s"].get<double>(), w["cycle_time_s"].get<double>() - 0.4, 1e-6) << "line 2 was not left out";

  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  const httplib::Result run = post("/api/program/run", kTabA, {{"gcode", kSquareAndArc}, {"from_line", 3}});
  ASSERT_TRUE(run);
  ASSERT_EQ(run->status, 200) << run->body;
  const nlohmann::json p = wait_program([](const nlohmann::json& s) { return s["phase"] == "ended"; }, "the run's end");
  EXPECT_EQ(p["end"], "done") << p.dump();
  EXPECT_EQ(p["line"], 4) << "the last line the node ran";
  bool logged = false;
  for (const nlohmann::json& line : audit_lines())
    if (line.value("path", "") == "/api/program/run") logged = line["body"].value("from_line", 0) == 3;
  EXPECT_TRUE(logged) << "the audit trail does not say the run started at line 3";
}

// Bad values are refused with the reason and start nothing: a field of the
// wrong kind before the run begins (the program stays idle), a line the
// interpreter cannot start at as a refused program (400 naming it).
TEST_F(ProgramPageTest, ABadRunFromLineIsRefusedAndStartsNothing) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  const std::pair<nlohmann::json, const char*> bad_fields[] = {
      {{{"from_line", 0}}, "from_line must be a whole number from 1"},
      {{{"from_line", 2.5}}, "from_line must be a whole number"},
      {{{"from_line", "3"}}, "from_line must be a whole number"},
      {{{"from_line", nullptr}}, "from_line must be a whole number"},
      {{{"from_line", 3}, {"from_pass", 0}}, "from_pass must be a whole number from 1"},
      {{{"from_line", 3}, {"tool_in_spindle", -1}}, "tool_in_spindle must be a whole number from 0"},
      {{{"from_line", 3}, {"approach_height_mm", -1.0}}, "approach_height_mm must be a number >= 0"},
      {{{"tool_in_spindle", 2}}, "tool_in_spindle needs from_line"},
  };
  for (const auto& [fields, why] : bad_fields) {
    nlohmann::json body = fields;
    body["gcode"] = kSquareAndArc;
    for (const char* route : {"/api/program/preview", "/api/program/run"}) {
      const httplib::Result r = post(route, kTabA, body);
      ASSERT_TRUE(r);
      EXPECT_EQ(r->status, 400) << route << " " << fields.dump() << ": " << r->body;
      EXPECT_NE(nlohmann::json::parse(r->body)["error"].get<std::string>().find(why), std::string::npos)
          << route << ": " << r->body;
    }
  }
  EXPECT_EQ(program()["phase"], "idle") << "a bad field began a run";

  const httplib::Result outside = post("/api/program/run", kTabA, {{"gcode", kSquareAndArc}, {"from_line", 99}});
  ASSERT_TRUE(outside);
  EXPECT_EQ(outside->status, 400) << outside->body;
  const nlohmann::json e = nlohmann::json::parse(outside->body);
  EXPECT_NE(e["error"].get<std::string>().find("cannot run from line 99"), std::string::npos) << outside->body;
  EXPECT_EQ(program()["end"], "refused");
  EXPECT_EQ(node_state(), "disabled") << "the servo was switched on for a refused start";
}

// The node's PROGRAM_TOOL in the program's state: unknown while the M6
// pause waits (a fresh node knows no tool either), the tool once Resume
// confirms the change (T0: the spindle emptied, which the node knows too).
TEST_F(ProgramPageTest, AConfirmedToolChangeShowsTheNodesToolInTheSpindle) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  const httplib::Result run = post("/api/program/run", kTabA, {{"gcode", "G21 G91 G17\nG1 X1 F600\nT0 M6\nG1 X-1\nM2\n"}});
  ASSERT_TRUE(run);
  ASSERT_EQ(run->status, 200) << run->body;
  const nlohmann::json paused = wait_program(
      [](const nlohmann::json& s) { return (!s["pause"].is_null() && !s["spindle_tool"].is_null()) || s["phase"] == "ended"; },
      "the tool change's pause");
  ASSERT_FALSE(paused["pause"].is_null()) << paused.dump();
  EXPECT_EQ(paused["pause"]["reason"], "tool change (M6)");
  EXPECT_EQ(paused["spindle_tool"]["known"], false) << paused.dump();
  EXPECT_EQ(paused["spindle_tool"]["text"], "unknown");
  ASSERT_EQ(post("/api/program/resume", kTabA)->status, 200);
  const nlohmann::json p = wait_program([](const nlohmann::json& s) { return s["phase"] == "ended"; }, "the run's end");
  EXPECT_EQ(p["end"], "done") << p.dump();
  ASSERT_FALSE(p["spindle_tool"].is_null()) << p.dump();
  EXPECT_EQ(p["spindle_tool"]["known"], true) << p.dump();
  EXPECT_EQ(p["spindle_tool"]["tool"], 0);
  EXPECT_EQ(p["spindle_tool"]["text"], "no tool");
}

// The optional stop and block delete switches, as --optional-stop and
// --block-delete: on by default (M1 pauses, '/' lines are skipped); off,
// the M1 runs through and the slashed line runs. A switch that is not
// true or false is 400 before anything starts.
TEST_F(ProgramPageTest, TheOptionalStopAndBlockDeleteSwitchesApplyAndAreCheckedFirst) {
  const std::string slashed = "G21 G91 G17\nG1 X1 F600\n/G1 Y1\nG1 X-1\nM2\n";
  const auto segments = [&](const nlohmann::json& body) {
    const httplib::Result r = post("/api/program/preview", kTabA, body);
    EXPECT_TRUE(r && r->status == 200) << (r ? r->body : "no answer");
    return r && r->status == 200 ? nlohmann::json::parse(r->body)["segments"].get<int>() : -1;
  };
  EXPECT_EQ(segments({{"gcode", slashed}}), 2) << "block delete is on by default";
  EXPECT_EQ(segments({{"gcode", slashed}, {"block_delete", true}}), 2);
  EXPECT_EQ(segments({{"gcode", slashed}, {"block_delete", false}}), 3) << "the slashed line did not run";

  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  for (const char* key : {"optional_stop", "block_delete"}) {
    const httplib::Result bad = post("/api/program/run", kTabA, {{"gcode", kShort}, {key, "off"}});
    ASSERT_TRUE(bad);
    EXPECT_EQ(bad->status, 400) << bad->body;
    EXPECT_NE(nlohmann::json::parse(bad->body)["error"].get<std::string>().find(std::string(key) + " must be true or false"),
              std::string::npos) << bad->body;
  }
  EXPECT_EQ(program()["phase"], "idle") << "a bad switch began a run";

  const httplib::Result run =
      post("/api/program/run", kTabA, {{"gcode", "G21 G91 G17\nG1 X1 F600\nM1\nG1 X-1\nM2\n"}, {"optional_stop", false}});
  ASSERT_TRUE(run);
  ASSERT_EQ(run->status, 200) << run->body;
  const nlohmann::json p = wait_program(
      [](const nlohmann::json& s) { return s["phase"] == "ended" || !s["pause"].is_null(); }, "the run's end");
  EXPECT_EQ(p["end"], "done") << "the M1 paused with the switch off: " << p.dump();
}

// The Feed hold button: the program brakes on its path and waits there
// (PROGRAM_STATUS holding, its progress standing still) until the hold is
// released, then goes on; only the tab with control holds, a hold that is
// not true or false is 400, and nothing running is 409.
TEST_F(ProgramPageTest, AFeedHoldWaitsOnThePathUntilReleased) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  const httplib::Result idle = post("/api/program/hold", kTabA, {{"hold", true}});
  ASSERT_TRUE(idle);
  EXPECT_EQ(idle->status, 409) << idle->body;
  run_until_halfway_started();
  const httplib::Result bad = post("/api/program/hold", kTabA, {{"hold", "yes"}});
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400) << bad->body;
  const httplib::Result other = post("/api/program/hold", kTabB, {{"hold", true}});
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 403) << other->body;
  const httplib::Result hold = post("/api/program/hold", kTabA, {{"hold", true}});
  ASSERT_TRUE(hold);
  ASSERT_EQ(hold->status, 200) << hold->body;
  const nlohmann::json held =
      wait_program([](const nlohmann::json& p) { return p["node_state"] == "holding" || p["phase"] == "ended"; },
                   "the node holding");
  ASSERT_EQ(held["node_state"], "holding") << held.dump();
  // Braking on the path may still finish the element it is in; after that nothing moves on.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const nlohmann::json at = program();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const nlohmann::json later = program();
  EXPECT_EQ(later["phase"], "running");
  EXPECT_EQ(later["node_state"], "holding");
  EXPECT_EQ(later["element"], at["element"]) << "it went on while held";
  EXPECT_LT(later["fraction"].get<double>(), 0.5);
  const httplib::Result go = post("/api/program/hold", kTabA, {{"hold", false}});
  ASSERT_TRUE(go);
  ASSERT_EQ(go->status, 200) << go->body;
  // It goes on (2 mm more of the path), then a Stop ends it without waiting out the other 10 s.
  const double from = later["fraction"].get<double>();
  const nlohmann::json on = wait_program(
      [from](const nlohmann::json& s) { return s["fraction"].get<double>() >= from + 0.02 || s["phase"] == "ended"; },
      "the program going on after the release");
  EXPECT_EQ(on["phase"], "running") << on.dump();
  EXPECT_EQ(on["node_state"], "running");
  ASSERT_EQ(post("/api/motion", kTabA, {{"kind", "stop"}})->status, 200);
}

// The page's tool table and .var file, as --tool-table and --var-file:
// a tool change needs its tool in the table, a G54 offset from the .var
// moves the path, a bad line is 400 naming the file and the line, and the
// audit trail keeps the files' digests, not their text.
TEST_F(ProgramPageTest, AToolTableAndAVarFileApplyAsOnTheCommandLine) {
  const std::string change = "G21 G91 G17\nG1 X1 F600\nT2 M6\nG1 X-1\nM2\n";
  const httplib::Result without = post("/api/program/preview", kTabA, {{"gcode", change}});
  ASSERT_TRUE(without);
  EXPECT_EQ(without->status, 400) << without->body;
  EXPECT_NE(without->body.find("requested tool 2 not found"), std::string::npos) << without->body;
  const httplib::Result with = post("/api/program/preview", kTabA, {{"gcode", change}, {"tool_table", "T2 P2 Z0 D6\n"}});
  ASSERT_TRUE(with);
  EXPECT_EQ(with->status, 200) << with->body;
  EXPECT_EQ(nlohmann::json::parse(with->body)["tool_changes"], 1);

  const std::string to_origin = "G21 G90 G17 G54\nG0 X7.25 Y1.5\nM2\n";
  const auto end_x = [&](const nlohmann::json& body) {
    const httplib::Result r = post("/api/program/preview", kTabA, body);
    EXPECT_TRUE(r && r->status == 200) << (r ? r->body : "no answer");
    if (!r || r->status != 200) return -1e9;
    const nlohmann::json pieces = nlohmann::json::parse(r->body)["pieces"];
    if (pieces.empty()) return -1e9;
    const nlohmann::json& points = pieces.back()["points"];
    return points[points.size() - 2].get<double>();
  };
  EXPECT_NEAR(end_x({{"gcode", to_origin}}), 7.25, 1e-9);
  EXPECT_NEAR(end_x({{"gcode", to_origin}, {"var_file", "5221\t12.5\n5222\t-3\n"}}), 19.75, 1e-9);

  const httplib::Result bad = post("/api/program/preview", kTabA, {{"gcode", change}, {"tool_table", "T2 P2 Z0\nT3 Q\n"}});
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400) << bad->body;
  EXPECT_NE(bad->body.find("tool_table: line 2"), std::string::npos) << bad->body;
  const httplib::Result wrong = post("/api/program/preview", kTabA, {{"gcode", change}, {"var_file", 5221}});
  ASSERT_TRUE(wrong);
  EXPECT_EQ(wrong->status, 400) << wrong->body;
  bool logged = false;
  for (const nlohmann::json& line : audit_lines())
    if (line.value("path", "") == "/api/program/preview" && line["body"].contains("tool_table") &&
        line["body"]["tool_table"].is_object())
      logged = line["body"]["tool_table"]["lines"] == 1 || logged;
  EXPECT_TRUE(logged) << "the tool table's digest is not in the audit trail";
}

TEST_F(ProgramPageTest, StopInterruptsARunningProgramAtOnce) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  run_until_halfway_started();
  const httplib::Result stop = post("/api/motion", kTabA, {{"kind", "stop"}});
  ASSERT_TRUE(stop);
  EXPECT_EQ(stop->status, 200) << stop->body;
  EXPECT_EQ(nlohmann::json::parse(stop->body)["program"], "interrupted") << stop->body;
  // The stop's answer comes after the program's job ended: no waiting here.
  const nlohmann::json p = program();
  EXPECT_EQ(p["phase"], "ended");
  EXPECT_EQ(p["end"], "interrupted") << p.dump();
  EXPECT_LT(p["fraction"].get<double>(), 0.5) << "the program ran on for 10 s of machine time after the stop";
  // The node is free again: a new run is accepted.
  const httplib::Result again = post("/api/program/run", kTabA, {{"gcode", "G91\nG1 X-1 F600\n"}});
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 200) << again->body;
  wait_program([](const nlohmann::json& s) { return s["phase"] == "ended"; }, "the second run's end");
}

TEST_F(ProgramPageTest, AnotherMotionIsRefusedWhileAProgramRuns) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  run_until_halfway_started();
  const httplib::Result move = post("/api/motion", kTabA, {{"kind", "move"}, {"distance_mm", 5.0}, {"speed_mm_s", 5.0}});
  ASSERT_TRUE(move);
  EXPECT_EQ(move->status, 409) << move->body;
  const httplib::Result second = post("/api/program/run", kTabA, {{"gcode", kShort}});
  ASSERT_TRUE(second);
  EXPECT_EQ(second->status, 409) << second->body;
  ASSERT_EQ(post("/api/motion", kTabA, {{"kind", "estop"}})->status, 200);
  EXPECT_EQ(program()["end"], "interrupted");
}

// The page's E-stop during a program goes out from the program's own job at
// its next look, before the stream brakes on its path and asks the node to
// abort: the node, e-stopped, has no program left to abort by then.
TEST_F(ProgramPageTest, EstopDuringAProgramReachesTheNodeBeforeTheProgramIsBraked) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  run_until_halfway_started();
  const httplib::Result estop = post("/api/motion", kTabA, {{"kind", "estop"}});
  ASSERT_TRUE(estop);
  EXPECT_EQ(estop->status, 200) << estop->body;
  const nlohmann::json p = program();
  EXPECT_EQ(p["end"], "interrupted") << p.dump();
  EXPECT_LT(p["fraction"].get<double>(), 0.5) << p.dump();
  // The node latched the remote e-stop (not only a stop on its path).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  std::string fault;
  while (std::chrono::steady_clock::now() < deadline) {
    const nlohmann::json st = nlohmann::json::parse(http_->Get("/api/status")->body);
    if (!st["heartbeat"].is_null()) fault = st["heartbeat"]["fault"].get<std::string>();
    if (fault == "remote_estop") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_EQ(fault, "remote_estop");
}

TEST(ProgramStateFlags, OnlyAnEstopAsksTheProgramsJobToSendOneAndANewRunForgetsIt) {
  ProgramState state;
  EXPECT_FALSE(state.interrupt(true)) << "nothing runs: nothing to interrupt";
  EXPECT_FALSE(state.estop_requested());
  ASSERT_TRUE(state.begin(nlohmann::json::object()));
  ASSERT_TRUE(state.interrupt());
  EXPECT_TRUE(state.interrupted());
  EXPECT_FALSE(state.estop_requested()) << "a stop brakes on the path; it sends no e-stop";
  ASSERT_TRUE(state.interrupt(true));
  EXPECT_TRUE(state.estop_requested());
  state.finish("interrupted", "");
  ASSERT_TRUE(state.begin(nlohmann::json::object()));
  EXPECT_FALSE(state.interrupted());
  EXPECT_FALSE(state.estop_requested());
}

TEST_F(ProgramPageTest, TheProgramRouteHasItsOwnBodyLimit) {
  std::string text = "G21 G90 G17 F100\n";
  while (text.size() < 100 * 1024) text += "(a CAM post's comment, long enough to fill a line of text) G1 X1 Y1\n";
  const httplib::Result preview = post("/api/program/preview", kTabA, {{"gcode", text}});
  ASSERT_TRUE(preview);
  EXPECT_EQ(preview->status, 200) << preview->body.substr(0, 200);
  const httplib::Result motion = post("/api/motion", kTabA, {{"kind", "stop"}, {"padding", text}});
  ASSERT_TRUE(motion);
  EXPECT_EQ(motion->status, 413);
}

class ProgramDeadmanTest : public ProgramPageTest {
 protected:
  std::chrono::milliseconds deadman() const override { return std::chrono::milliseconds(300); }
};

TEST_F(ProgramDeadmanTest, ATabThatGoesQuietHasItsProgramInterrupted) {
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  std::atomic<bool> silent{false};
  std::thread heart([&] {
    httplib::Client c("127.0.0.1", port_);
    c.set_default_headers({{"Authorization", "Bearer " + server_->secret()}, {"Origin", origin()}, {"X-Tnv-Token", kTabA}});
    while (!silent) {
      c.Post("/api/control/heartbeat", "", "application/json");
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  run_until_halfway_started();
  silent = true;
  heart.join();
  const nlohmann::json p = wait_program([](const nlohmann::json& s) { return s["phase"] == "ended"; }, "the run's end");
  EXPECT_EQ(p["end"], "interrupted") << p.dump();
  EXPECT_LT(p["fraction"].get<double>(), 0.5);
  bool logged = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!logged && std::chrono::steady_clock::now() < deadline) {
    for (const nlohmann::json& line : audit_lines())
      if (line.value("event", "") == "dead-man" &&
          line["detail"].get<std::string>().find("program interrupted") != std::string::npos)
        logged = true;
    if (!logged) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_TRUE(logged) << "no dead-man line naming the program in the audit trail";
}

}  // namespace
}  // namespace tnv::serve
