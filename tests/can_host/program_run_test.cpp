// Streaming a program to the emulated node over the virtual 1 Mbit/s bus
// (tools/can/program_stream.hpp, program_run.hpp): flow control fills the
// queue without overflowing it, a paused host causes exactly one underrun
// and the run still ends on the path, an interrupt stops on the path, a
// second host cannot stream, and control traffic keeps flowing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "firmware/can/node_fields.hpp"
#include "firmware/can/param_table.hpp"
#include "tests/tools/gcode/test_piece_path.hpp"
#include "tools/can/program_run.hpp"
#include "tools/can_emu/emulated_bus.hpp"
#include "tools/gcode/path_distance.hpp"

namespace tnv {
namespace {

namespace can = fw::can;
using can_host::Micros;
using can_host::StreamResult;

std::string read_program_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

struct StreamBench {
  explicit StreamBench(const std::string& name) {
    o.storage_path = (std::filesystem::temp_directory_path() / ("tnv_stream_" + std::to_string(::getpid()) + name)).string();
    std::string error;
    bus = can_host::EmulatedBus::create(o, error);
    EXPECT_TRUE(bus) << error;
  }
  ~StreamBench() {
    std::error_code ignored;
    std::filesystem::remove(o.storage_path, ignored);
  }
  can_host::EmulatedNodeOptions o;
  std::unique_ptr<can_host::EmulatedBus> bus;
};

// 150 lines of 0.5 mm at 2 mm/s: the host streams far faster than the table runs them.
std::string slow_zigzag() {
  std::string text = "G17 G21 G91 F120\n";
  for (int i = 0; i < 75; ++i) text += "G1 X0.5 Y0.2\nG1 X0.5 Y-0.2\n";
  return text;
}

double stream_ms(Micros t) { return static_cast<double>(t.count()) / 1000.0; }

double reference_deviation_max_um(const can_host::ProgramRunResult& r) {
  const gcode::ProgrammedPath path(r.program.geometry);
  double worst = 0.0;
  for (const hil::PathSample& s : r.samples) worst = std::max(worst, path.distance_mm(s.reference_mm) * 1e3);
  return worst;
}

TEST(ProgramStream, FlowControlFillsTheQueueAndNeverOverflowsIt) {
  StreamBench b("flow");
  ASSERT_TRUE(b.bus);
  can_host::NodeClient client(*b.bus, 1);
  const can_host::ProgramRunResult r = can_host::run_gcode(client, slow_zigzag(), {});
  const StreamResult& s = r.stream;
  ASSERT_EQ(s.end, StreamResult::End::done) << s.message;
  EXPECT_EQ(s.acknowledged, 150u);
  EXPECT_EQ(s.min_free_slots, 0) << "the queue was never full: flow control was not exercised";
  EXPECT_LE(s.max_in_flight, 12u);
  EXPECT_EQ(s.underruns, 0u);
  EXPECT_EQ(s.queue_capacity, fw::motion::kSegmentQueueCapacity);
  std::printf("[stream] the queue filled at %.0f elements/s (line elements, 2 frames + 1 ack each, 1 Mbit/s, "
              "telemetry every 1 ms)\n",
              s.fill_elements_per_s);
  EXPECT_GT(s.fill_elements_per_s, 1000.0);
  ASSERT_TRUE(r.score);
  EXPECT_TRUE(r.telemetry_complete);
  EXPECT_LE(r.score->path_deviation_max_um, 5.0 + 2e-3);
}

TEST(ProgramStream, APausedHostCausesOneUnderrunAndTheProgramStillEndsOnThePath) {
  StreamBench b("underrun");
  ASSERT_TRUE(b.bus);
  can_host::NodeClient client(*b.bus, 1);
  can_host::ProgramRunOptions o;
  o.before_send = [&client](std::size_t k) {
    if (k == 300) client.pump(Micros{400'000});  // 0.4 s without a frame: the queue runs dry
  };
  const can_host::ProgramRunResult r =
      can_host::run_gcode(client, read_program_text(gcode::test::test_piece_path("circle_chords_0p1mm.ngc")), o);
  ASSERT_EQ(r.stream.end, StreamResult::End::done) << r.stream.message;
  EXPECT_EQ(r.stream.underruns, 1u);
  ASSERT_TRUE(r.stream.final_heartbeat);
  EXPECT_EQ(r.stream.final_heartbeat->fault, fw::FaultReason::none);
  ASSERT_TRUE(r.score);
  std::printf("[stream] paused host: underruns %llu, path deviation max %.3f um, contour error max %.3f um\n",
              static_cast<unsigned long long>(r.stream.underruns), r.score->path_deviation_max_um,
              r.score->contour_error_max_um);
  EXPECT_LE(r.score->path_deviation_max_um, 5.0 + 2e-3) << "the reference left the path (+ telemetry rounding)";
  const fw::motion::PlanePoint end = r.samples.back().reference_mm;
  const fw::motion::PlanePoint last = r.program.geometry.back().end_mm;
  EXPECT_LT(std::hypot(end[0] - last[0], end[1] - last[1]), 2e-4) << "ends on the program's last point";
}

// Z over the bus (protocol 8): a plunge, a contour at depth, a G2 helix and a retract, each element
// that moves Z with its SEGMENT_Z; the telemetry's Z follows and the run is scored in 3-D.
TEST(ProgramStream, AProgramThatMovesZRunsOverTheBusAndItsZFollows) {
  StreamBench b("z");
  ASSERT_TRUE(b.bus);
  can_host::NodeClient client(*b.bus, 1);
  const char* text =
      "G21 G91\nG1 Z-5 F300\nG1 X20 F1200\nG1 Y10\nG1 X-20\nG2 X0 Y0 Z-2 I0 J-5 F600\nG0 Z7\nM2\n";
  const can_host::ProgramRunResult r = can_host::run_gcode(client, text, {});
  ASSERT_EQ(r.stream.end, StreamResult::End::done) << r.stream.message;
  ASSERT_TRUE(r.stream.final_heartbeat);
  EXPECT_EQ(r.stream.final_heartbeat->fault, fw::FaultReason::none);
  std::size_t with_z = 0;
  for (const can_host::WireElement& e : r.wire.elements) with_z += e.frames.has_z ? 1u : 0u;
  EXPECT_GE(with_z, 3u) << "the plunge, the helix (in pieces or whole) and the retract carry SEGMENT_Z";
  EXPECT_LT(with_z, r.wire.elements.size()) << "the contour at depth keeps two frames";
  ASSERT_TRUE(r.score);
  ASSERT_FALSE(r.samples.empty());
  constexpr std::size_t z = fw::can::kProgramZ;
  const double z0 = r.start_mm[z];
  double z_min = z0;
  for (const hil::PathSample& s : r.samples) z_min = std::min(z_min, s.position_mm[z]);
  EXPECT_NEAR(z_min, z0 - 7.0, 0.01) << "the helix ends 7 mm below the start";
  EXPECT_NEAR(r.samples.back().reference_mm[z], z0, 2e-6) << "retracted";
  std::printf("[stream] Z program over the bus: contour max %.3f um, path deviation %.3f um, %zu of %zu elements "
              "with SEGMENT_Z\n",
              r.score->contour_error_max_um, r.score->path_deviation_max_um, with_z, r.wire.elements.size());
  EXPECT_LE(r.score->path_deviation_max_um, 5.0 + 2e-3);
  EXPECT_LE(r.score->contour_error_max_um, 6.0);
}

// Arcs in G18 and G19 over the bus (protocol 9): each with its SEGMENT_PLANE (a full turn in
// pieces: no chord for a whole one); the telemetry follows them and the run is scored in 3-D.
TEST(ProgramStream, ArcsInG18AndG19RunOverTheBusInTheirPlanes) {
  StreamBench b("planes");
  ASSERT_TRUE(b.bus);
  can_host::NodeClient client(*b.bus, 1);
  const char* text =
      "G21 G91\nG1 Z-10 F300\nG18 G2 X10 Z0 I5 K0 Y-2 F600\nG19 G3 Y10 Z0 J5 K0 X2\n"
      "G18 G3 X0 Z0 I0 K-3 Y3 P2\nG17 G0 Z10\nM2\n";
  const can_host::ProgramRunResult r = can_host::run_gcode(client, text, {});
  ASSERT_EQ(r.stream.end, StreamResult::End::done) << r.stream.message;
  ASSERT_TRUE(r.stream.final_heartbeat);
  EXPECT_EQ(r.stream.final_heartbeat->fault, fw::FaultReason::none);
  std::size_t with_plane = 0;
  for (const can_host::WireElement& e : r.wire.elements)
    with_plane += e.frames.has_z && e.frames.z.dlc == fw::can::fields::kSegmentPlaneMsg.dlc ? 1u : 0u;
  EXPECT_GE(with_plane, 4u) << "two half turns and two full turns (sent in halves) carry SEGMENT_PLANE";
  ASSERT_TRUE(r.score);
  ASSERT_FALSE(r.samples.empty());
  constexpr std::size_t z = fw::can::kProgramZ;
  const double z0 = r.start_mm[z];
  double z_min = z0;
  for (const hil::PathSample& s : r.samples) z_min = std::min(z_min, s.reference_mm[z]);
  EXPECT_NEAR(z_min, z0 - 16.0, 1e-3) << "the full turns in G18 reach 6 mm below the plunge";
  EXPECT_NEAR(r.samples.back().reference_mm[z], z0, 2e-6) << "retracted";
  std::printf("[stream] G18/G19 over the bus: contour max %.3f um, path deviation %.3f um, %zu of %zu elements "
              "with SEGMENT_PLANE\n",
              r.score->contour_error_max_um, r.score->path_deviation_max_um, with_plane, r.wire.elements.size());
  EXPECT_LE(r.score->path_deviation_max_um, 5.0 + 2e-3);
  EXPECT_LE(r.score->contour_error_max_um, 6.0);
}

TEST(ProgramStream, AnInterruptStopsOnThePathAndDropsTheRest) {
  StreamBench b("interrupt");
  ASSERT_TRUE(b.bus);
  can_host::NodeClient client(*b.bus, 1);
  can_host::ProgramRunOptions o;
  double fraction = 0.0;
  o.progress = [&fraction](const can_host::StreamProgress& p) { fraction = p.fraction; };
  o.interrupted = [&fraction] { return fraction > 0.3; };
  const can_host::ProgramRunResult r = can_host::run_gcode(client, slow_zigzag(), o);
  EXPECT_EQ(r.stream.end, StreamResult::End::interrupted) << r.stream.message;
  EXPECT_EQ(r.stream.final_status.state, can::ProgramState::aborted);
  EXPECT_EQ(b.bus->rig().task.state(), fw::MotionState::holding);
  EXPECT_EQ(b.bus->rig().task.motion().queued(), 0u);
  EXPECT_LE(reference_deviation_max_um(r), 5.0 + 2e-3);
  const fw::motion::PlanePoint rest = r.samples.back().reference_mm;
  EXPECT_LT(rest[0] - r.start_mm[0], 0.6 * 75.0) << "stopped well before the end";
  EXPECT_FALSE(r.score) << "an interrupted program is not scored";
}

TEST(ProgramStream, ASecondHostCannotStreamWhileAnotherOwnsTheNode) {
  StreamBench b("hosts");
  ASSERT_TRUE(b.bus);
  can_host::ClientOptions one;
  one.host_id = 1;
  can_host::ClientOptions two;
  two.host_id = 2;
  can_host::NodeClient a(*b.bus, 1, one);
  can_host::NodeClient c(*b.bus, 1, two);
  a.command(can::CommandCode::enable);
  gcode::GcodeOptions g;
  g.start_mm = b.bus->rig().task.next_segment_start_mm();
  const gcode::GcodeResult parsed = gcode::parse_gcode(slow_zigzag(), g);
  std::string error;
  const std::optional<can_host::WireProgram> wire = can_host::wire_program(parsed.program, g.start_mm, 1, error);
  ASSERT_TRUE(wire) << error;
  const StreamResult s = can_host::stream_program(c, *wire, {});
  EXPECT_EQ(s.end, StreamResult::End::failed);
  EXPECT_NE(s.message.find("not_owner"), std::string::npos) << s.message;
  EXPECT_NE(s.message.find("host 1 owns"), std::string::npos) << s.message;
  EXPECT_EQ(s.acknowledged, 0u);
  EXPECT_EQ(b.bus->rig().task.motion().queued(), 0u);
  EXPECT_FALSE(b.bus->rig().task.program_running());
}

TEST(ProgramStream, HeartbeatRepliesAndFaultEventsKeepFlowingWhileAProgramStreams) {
  StreamBench b("priority");
  ASSERT_TRUE(b.bus);
  can_host::NodeClient client(*b.bus, 1);
  client.set(*can::find_param("tlm.position_ms"), 1);
  client.command(can::CommandCode::enable);
  gcode::GcodeOptions g;
  g.start_mm = b.bus->rig().task.next_segment_start_mm();
  const gcode::GcodeResult parsed = gcode::parse_gcode(read_program_text(gcode::test::test_piece_path("circle_chords_0p1mm.ngc")), g);
  std::string error;
  const std::optional<can_host::WireProgram> wire = can_host::wire_program(parsed.program, g.start_mm, 1, error);
  ASSERT_TRUE(wire) << error;

  std::vector<Micros> heartbeats;
  Micros reply_wait{0};
  Micros estop_at{-1};
  Micros fault_event_at{-1};
  can_host::StreamOptions o;
  o.on_frame = [&](const hal::CanFrame&, can::MessageId id) {
    if (id == can::MessageId::heartbeat && estop_at.count() < 0) heartbeats.push_back(b.bus->now());
    if (id == can::MessageId::fault_event && fault_event_at.count() < 0) fault_event_at = b.bus->now();
  };
  o.before_send = [&](std::size_t k) {
    if (k == 300) {
      const Micros t0 = b.bus->now();
      client.get(*can::find_param("x.sliding.gamma"));
      reply_wait = b.bus->now() - t0;
    }
    if (k == 500) {
      estop_at = b.bus->now();
      client.estop(false);
    }
  };
  const StreamResult s = can_host::stream_program(client, *wire, o);
  EXPECT_EQ(s.end, StreamResult::End::failed) << "the e-stop ends the run";
  Micros gap_max{0};
  for (std::size_t k = 1; k < heartbeats.size(); ++k) gap_max = std::max(gap_max, heartbeats[k] - heartbeats[k - 1]);
  std::printf("[stream] while streaming with 1 ms telemetry: heartbeat gap max %.1f ms over %zu heartbeats, a "
              "parameter get answered in %.2f ms, FAULT_EVENT %.2f ms after the ESTOP\n",
              stream_ms(gap_max), heartbeats.size(), stream_ms(reply_wait), stream_ms(fault_event_at - estop_at));
  ASSERT_GE(heartbeats.size(), 20u);
  EXPECT_LE(gap_max, Micros{105'000}) << "tlm.heartbeat_ms is 100";
  EXPECT_LE(reply_wait, Micros{5'000});
  ASSERT_GE(fault_event_at.count(), 0) << "no FAULT_EVENT";
  EXPECT_LE(fault_event_at - estop_at, Micros{5'000});
}

}  // namespace
}  // namespace tnv
