// Program pauses over the virtual bus to the emulated node (issue 28): M0,
// M1 (with the optional stop switch on, and run through with it off) and
// M6 pause the streamed program at rest; the host is told the line, the
// reason and the tool, and the program goes on only when the caller says so
// (COMMAND cycle_start); without a caller that continues, the run stops at
// the first pause. The paused runs end where the same program without
// pauses ends. After M6 the node knows the tool (PROGRAM_TOOL), and a node
// started again does not.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <vector>

#include "tools/can/program_run.hpp"
#include "tools/can_emu/emulated_bus.hpp"
#include "tools/gcode/path_distance.hpp"

namespace tnv {
namespace {

namespace can = fw::can;
using can_host::Micros;
using can_host::StreamResult;
using gcode::PauseReason;

struct PauseBench {
  explicit PauseBench(const std::string& name) {
    o.storage_path = (std::filesystem::temp_directory_path() / ("tnv_pause_" + std::to_string(::getpid()) + name)).string();
    std::string error;
    bus = can_host::EmulatedBus::create(o, error);
    EXPECT_TRUE(bus) << error;
  }
  ~PauseBench() {
    std::error_code ignored;
    std::filesystem::remove(o.storage_path, ignored);
  }
  can_host::EmulatedNodeOptions o;
  std::unique_ptr<can_host::EmulatedBus> bus;
};

// Relative moves with an M0 (line 3), an M1 (line 5) and a manual tool change to T2 (line 7).
constexpr const char* kPausing =
    "G17 G21 G91 F600\n"  // 1
    "G1 X3\n"             // 2
    "M0\n"                // 3
    "G1 Y3\n"             // 4
    "M1\n"                // 5
    "G1 X-2 Y1\n"         // 6
    "T2 M6\n"             // 7
    "G1 X4\n"             // 8
    "M2\n";
constexpr const char* kWithoutPauses = "G17 G21 G91 F600\nG1 X3\nG1 Y3\nG1 X-2 Y1\nG1 X4\nM2\n";

// Tool 2 for the M6 (no length: Z does not move on this table).
gcode::CanonSetup pause_setup() {
  gcode::CanonSetup setup;
  std::string error;
  EXPECT_TRUE(setup.tools.load_text("T2 P2 Z0\n", error)) << error;
  return setup;
}

fw::motion::PlanePoint held(can_host::EmulatedBus& bus) {
  const fw::TickRecord& r = bus.rig().task.last_record();
  return {r.axis[0].reference_mm, r.axis[1].reference_mm};
}

struct PausedRun {
  can_host::ProgramRunResult result;
  std::vector<can_host::StreamPause> told;  // on_pause
  double moved_while_paused_mm = 0.0;       // the reference's largest move while the node said paused
};

PausedRun run_resuming(PauseBench& b, const std::string& text, bool optional_stop, Micros wait) {
  can_host::NodeClient client(*b.bus, 1);
  PausedRun out;
  can_host::ProgramRunOptions o;
  o.canon = pause_setup();
  o.canon.optional_stop = optional_stop;
  fw::motion::PlanePoint at{};
  o.on_pause = [&](const can_host::StreamPause& p) {
    out.told.push_back(p);
    at = held(*b.bus);
  };
  o.resume = [&](const can_host::StreamPause&, Micros paused_for) {
    const fw::motion::PlanePoint now = held(*b.bus);
    out.moved_while_paused_mm = std::max(out.moved_while_paused_mm, std::hypot(now[0] - at[0], now[1] - at[1]));
    return paused_for >= wait;
  };
  out.result = can_host::run_gcode(client, text, o);
  return out;
}

TEST(ProgramPause, M0M1AndM6PauseAtRestAndTheRunEndsWhereTheRunWithoutThemEnds) {
  PauseBench plain("plain");
  ASSERT_TRUE(plain.bus);
  can_host::NodeClient plain_client(*plain.bus, 1);
  const can_host::ProgramRunResult reference = can_host::run_gcode(plain_client, kWithoutPauses, {});
  ASSERT_EQ(reference.stream.end, StreamResult::End::done) << reference.stream.message;
  EXPECT_TRUE(reference.stream.pauses.empty());

  PauseBench b("on");
  ASSERT_TRUE(b.bus);
  const PausedRun run = run_resuming(b, kPausing, true, Micros{300'000});
  const can_host::ProgramRunResult& r = run.result;
  ASSERT_EQ(r.stream.end, StreamResult::End::done) << r.stream.message;
  ASSERT_EQ(run.told.size(), 3u);
  ASSERT_EQ(r.stream.pauses.size(), 3u);
  const int lines[] = {3, 5, 7};
  const PauseReason reasons[] = {PauseReason::program_stop, PauseReason::optional_stop, PauseReason::tool_change};
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(run.told[k].line, lines[k]);
    ASSERT_TRUE(run.told[k].why);
    EXPECT_EQ(run.told[k].why->reason, reasons[k]);
  }
  EXPECT_EQ(run.told[2].why->tool, 2);
  EXPECT_EQ(can_host::pause_text(run.told[2]), "line 7: tool change (M6), tool 2");
  EXPECT_LT(run.moved_while_paused_mm, 1e-6) << "the table moved while paused";
  EXPECT_GE(r.stream.paused_s, 3 * 0.3) << "each pause waited for the caller";
  EXPECT_EQ(r.stream.underruns, 0u);
  ASSERT_TRUE(r.stream.final_heartbeat);
  EXPECT_EQ(r.stream.final_heartbeat->fault, fw::FaultReason::none);
  const fw::motion::PlanePoint end = held(*b.bus);
  const fw::motion::PlanePoint plain_end = held(*plain.bus);
  EXPECT_LT(std::hypot(end[0] - plain_end[0], end[1] - plain_end[1]), 1e-6) << "ends where the run without pauses ends";
  ASSERT_TRUE(r.score);
  EXPECT_LE(r.score->path_deviation_max_um, 5.0 + 2e-3);
}

TEST(ProgramPause, AfterAConfirmedToolChangeTheNodeKnowsTheToolAndARestartForgetsIt) {
  PauseBench b("tool");
  ASSERT_TRUE(b.bus);
  {
    can_host::NodeClient client(*b.bus, 1);
    EXPECT_EQ(client.program_tool(), can_host::ProgramTool{}) << "a node just started knows no tool";
  }
  const PausedRun first = run_resuming(b, kPausing, true, Micros{100'000});
  ASSERT_EQ(first.result.stream.end, StreamResult::End::done) << first.result.stream.message;
  ASSERT_TRUE(first.result.stream.final_tool);
  EXPECT_EQ(*first.result.stream.final_tool, (can_host::ProgramTool{true, 2}));

  // The next change: unknown while the operator changes it (the node's word at the pause), tool 5 after.
  can_host::NodeClient client(*b.bus, 1);
  can_host::ProgramRunOptions o;
  o.canon = pause_setup();
  std::string error;
  ASSERT_TRUE(o.canon.tools.load_text("T5 P5 Z0\n", error)) << error;
  std::optional<can_host::ProgramTool> at_the_pause;
  o.resume = [&](const can_host::StreamPause&, Micros paused_for) {
    at_the_pause = client.last_program_tool();  // the last look before going on
    return paused_for >= Micros{100'000};
  };
  std::vector<can_host::ProgramTool> progress_tools;
  o.progress = [&](const can_host::StreamProgress& p) {
    if (p.tool && (progress_tools.empty() || progress_tools.back() != *p.tool)) progress_tools.push_back(*p.tool);
  };
  const can_host::ProgramRunResult r = can_host::run_gcode(client, "G17 G21 G91 F600\nG1 X2\nT5 M6\nG1 X-2\nM2\n", o);
  ASSERT_EQ(r.stream.end, StreamResult::End::done) << r.stream.message;
  ASSERT_TRUE(at_the_pause);
  EXPECT_FALSE(at_the_pause->known) << "the node claimed a tool while it was being changed";
  EXPECT_EQ(progress_tools, (std::vector<can_host::ProgramTool>{{true, 2}, {}, {true, 5}}));
  EXPECT_EQ(client.program_tool(), (can_host::ProgramTool{true, 5}));

  // The node starts again on the same storage: it does not know the tool (never guessed from the last run).
  b.bus.reset();
  b.bus = can_host::EmulatedBus::create(b.o, error);
  ASSERT_TRUE(b.bus) << error;
  can_host::NodeClient restarted(*b.bus, 1);
  EXPECT_EQ(restarted.program_tool(), can_host::ProgramTool{});
}

TEST(ProgramPause, WithTheOptionalStopSwitchOffM1RunsThrough) {
  PauseBench b("off");
  ASSERT_TRUE(b.bus);
  const PausedRun run = run_resuming(b, kPausing, false, Micros{100'000});
  ASSERT_EQ(run.result.stream.end, StreamResult::End::done) << run.result.stream.message;
  ASSERT_EQ(run.told.size(), 2u);
  EXPECT_EQ(run.told[0].line, 3);
  EXPECT_EQ(run.told[1].line, 7);
  EXPECT_EQ(run.result.program.optional_stops_skipped, 1u);
}

TEST(ProgramPause, NobodyToContinueStopsTheRunAtTheFirstPause) {
  PauseBench b("none");
  ASSERT_TRUE(b.bus);
  can_host::NodeClient client(*b.bus, 1);
  can_host::ProgramRunOptions o;
  o.canon = pause_setup();
  const can_host::ProgramRunResult r = can_host::run_gcode(client, kPausing, o);
  EXPECT_EQ(r.stream.end, StreamResult::End::failed);
  EXPECT_NE(r.stream.message.find("paused at line 3: program stop (M0)"), std::string::npos) << r.stream.message;
  EXPECT_EQ(r.stream.final_status.state, can::ProgramState::aborted);
  EXPECT_EQ(b.bus->rig().task.state(), fw::MotionState::holding);
  EXPECT_EQ(b.bus->rig().task.motion().queued(), 0u);
  const fw::motion::PlanePoint rest = held(*b.bus);
  EXPECT_NEAR(rest[0] - r.start_mm[0], 3.0, 1e-6) << "stopped at the M0, never past it";
  EXPECT_NEAR(rest[1] - r.start_mm[1], 0.0, 1e-6);
}

}  // namespace
}  // namespace tnv
