// Bus flood on the emulated bus (docs/safety.md "Bus flood"): a host keeps
// the 1 Mbit/s wire saturated with a mix of valid read-only requests for
// the node, malformed frames for it, frames for other node ids, broadcast
// and extended frames, while the node runs the S1 circle. The controller
// must not notice: no missed tick, the contour error of the circle equal to
// the same circle without the flood, the telemetry it could not send
// counted (and flagged in the heartbeat once the bus is free), and an
// ESTOP sent into the flood makes the outputs safe on the first tick after
// the node received it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <random>

#include "firmware/can/param_table.hpp"
#include "tests/firmware/can/can_test_doubles.hpp"
#include "tools/can_emu/emulated_bus.hpp"
#include "tools/score/contour_stats.hpp"

namespace tnv {
namespace {

namespace can = fw::can;
using can::MessageId;
using can_host::EmulatedBus;
using can_host::Micros;

constexpr std::uint8_t kFloodNode = 1;
// Host frames kept queued at each tick: more than fit on the wire in one
// tick (9 to 21 at 1 Mbit/s), so it never idles for want of one.
constexpr std::size_t kBacklog = 24;

std::unique_ptr<EmulatedBus> make_flood_bus(const char* name) {
  std::string file = "tnv_flood_";
  file.append(std::to_string(::getpid())).append("_").append(name);
  can_host::EmulatedNodeOptions o;
  o.storage_path = (std::filesystem::temp_directory_path() / file).string();  // never saved to
  std::string error;
  auto bus = EmulatedBus::create(o, error);
  EXPECT_TRUE(bus) << error;
  return bus;
}

// The flooding host: one frame of the mix per call, none of which may change
// the node's parameters or motion. Every identifier is below the node's
// telemetry (0x280 and up), so telemetry loses every arbitration while the
// flood lasts; the node's replies (COMMAND_ACK 0x061, PARAM_REPLY 0x121)
// still win against part of it.
class Flooder {
 public:
  // shortest: only 0-byte frames for other nodes, 47 bits each, the most
  // frames a 1 Mbit/s wire can carry (21 per millisecond).
  explicit Flooder(bool shortest = false) : shortest_(shortest) {}
  hal::CanFrame next() {
    using namespace test;
    if (shortest_) {
      const auto other = static_cast<std::uint8_t>(2 + pick(30));
      return hal::CanFrame{can::make_can_id(static_cast<std::uint8_t>(pick(13)), other), false, 0, {}};
    }
    const auto params = can::param_table();
    switch (kind_++ % 9) {
      case 0:  // valid: read a parameter
        return param_request(kFloodNode, can::ParamOp::get, params[pick(params.size())].id);
      case 1:  // valid: capture status
        return capture_control(kFloodNode, can::CaptureOp::status);
      case 2: {  // malformed for us: wrong length
        hal::CanFrame f = param_request(kFloodNode, can::ParamOp::set, params[pick(params.size())].id, 0);
        f.dlc = static_cast<std::uint8_t>(pick(8));
        return f;
      }
      case 3:  // malformed for us: no such command
        return command(kFloodNode, static_cast<can::CommandCode>(can::kCommandCodeCount + pick(200)));
      case 4: {  // for another node: anything, even stop and e-stop
        const auto other = static_cast<std::uint8_t>(2 + pick(30));
        return pick(2) == 0 ? command(other, can::CommandCode::stop) : frame_to(MessageId::estop, other);
      }
      case 5:  // broadcast, but not one of the two broadcasts a node obeys
        return command(can::kBroadcastNode, can::CommandCode::enable);
      case 6: {  // extended identifier
        hal::CanFrame f{static_cast<std::uint32_t>(rng_() & 0x3FFu), true, 8, {}};
        for (auto& b : f.data) b = static_cast<std::uint8_t>(rng_());
        return f;
      }
      case 7:  // a message id nobody defined
        return hal::CanFrame{can::make_can_id(0x11, kFloodNode), false, static_cast<std::uint8_t>(pick(9)), {}};
      default:  // a to-host message under our id (a spoofed heartbeat)
        return frame_to(MessageId::heartbeat, kFloodNode);
    }
  }
  std::uint64_t sent = 0;

 private:
  std::size_t pick(std::size_t n) { return static_cast<std::size_t>(rng_() % n); }
  std::mt19937 rng_{4711};
  unsigned kind_ = 0;
  bool shortest_ = false;
};

struct CircleRun {
  hil::ContourStats contour;
  std::uint64_t ticks = 0;
  std::uint64_t missed_ticks = 0;
  std::uint64_t late_ticks = 0;
  std::uint64_t flood_frames = 0;
  double motion_s = 0.0;
  double load = 0.0;  // busy bits / bits, while the circle ran
  can::NodeCounters node{};
  std::uint64_t rx_fifo_overflows = 0;
  // e-stop (when sent)
  std::int64_t estop_sent_tick = -1, estop_arrival_tick = -1, estop_safe_tick = -1;
  std::size_t estop_frames_ahead = 0;
  bool tx_dropped_flag_seen = false;
};

// The scenario's circle through the node; with `flood`, the wire saturated
// throughout; with `estop_at_motion_tick` >= 0, an ESTOP sent into the flood then.
CircleRun run_circle(const char* name, bool flood, std::int64_t estop_at_motion_tick = -1, bool shortest = false) {
  CircleRun out;
  auto bus = make_flood_bus(name);
  if (!bus) return out;
  const emu::Scenario& sc = bus->scenario();
  bus->send(test::command(kFloodNode, can::CommandCode::take_ownership));
  bus->send(test::circle(kFloodNode, sc.circle.radius_mm, sc.circle.feed_mm_s));
  const auto drain_host = [&] {
    while (bus->receive(Micros{0})) {
    }
  };
  Flooder flooder(shortest);
  hil::ContourAccumulator contour;
  const std::uint32_t mid = bus->rig().machine.dac_mid_code();
  std::uint64_t busy_at_start = 0;
  Micros motion_start{-1};
  std::uint64_t estop_target = 0;  // delivered_to_node + dropped_at_node once the e-stop is through
  const fw::TickTask& task = bus->rig().task;
  bool started = false;
  for (std::int64_t k = 0; k < 40'000; ++k) {
    if (flood) {
      while (bus->wire().pending(can_host::BusSide::host) < kBacklog) {
        bus->send(flooder.next());
        ++out.flood_frames;
      }
    }
    const fw::TickRecord& rec = task.last_record();
    if (estop_at_motion_tick >= 0 && out.estop_sent_tick < 0 && rec.motion_tick >= estop_at_motion_tick) {
      out.estop_frames_ahead = bus->wire().pending(can_host::BusSide::host);
      const auto& c = bus->wire().counters();
      estop_target = c.delivered_to_node + c.dropped_at_node + out.estop_frames_ahead + 1;
      bus->send(test::frame_to(MessageId::estop, kFloodNode));
      out.estop_sent_tick = k;
    }
    bus->step();
    drain_host();
    if (out.estop_sent_tick >= 0) {
      const auto& c = bus->wire().counters();
      if (out.estop_arrival_tick < 0 && c.delivered_to_node + c.dropped_at_node >= estop_target)
        out.estop_arrival_tick = k;
      if (out.estop_safe_tick < 0 && bus->rig().machine.board_outputs().safe(mid)) {
        out.estop_safe_tick = k;
        break;
      }
    }
    const fw::TickRecord& r = task.last_record();
    if (r.motion_tick >= 0) {
      if (!started) {
        started = true;
        motion_start = bus->now();
        busy_at_start = bus->wire().counters().busy_bits;
      }
      contour.add(hil::contour_error_mm(r.axis[0].reference_mm, r.axis[1].reference_mm, r.axis[0].position_mm,
                                        r.axis[1].position_mm));
    } else if (started) {
      break;  // the circle is done
    }
  }
  out.motion_s = static_cast<double>((bus->now() - motion_start).count()) * 1e-6;
  out.load = static_cast<double>(bus->wire().counters().busy_bits - busy_at_start) /
             (out.motion_s * static_cast<double>(bus->wire().bitrate_bit_s()));
  out.contour = contour.stats();
  out.ticks = task.counters().ticks;
  out.missed_ticks = task.counters().missed_ticks;
  out.late_ticks = task.counters().late_ticks;
  out.node = bus->node().counters();
  out.rx_fifo_overflows = bus->wire().counters().dropped_at_node;
  // The flood is over: the next heartbeat carries the drop flag.
  for (int k = 0; k < 250 && !out.tx_dropped_flag_seen; ++k) {
    bus->step();
    while (const auto f = bus->receive(Micros{0})) {
      if (test::is(*f, MessageId::heartbeat) &&
          (test::raw_of(*f, MessageId::heartbeat, "errors") & can::kHbTxDropped) != 0)
        out.tx_dropped_flag_seen = true;
    }
  }
  return out;
}

TEST(BusFlood, ASaturatedBusLeavesTheCircleUnchangedAndDropsAreCounted) {
  const CircleRun quiet = run_circle("quiet", false);
  const CircleRun flood = run_circle("flood", true);
  ASSERT_GT(quiet.contour.samples, 10'000u) << "the circle did not run";
  ASSERT_EQ(flood.contour.samples, quiet.contour.samples) << "ticks of motion";

  EXPECT_EQ(flood.missed_ticks, 0u);
  EXPECT_EQ(flood.late_ticks, 0u);
  EXPECT_NEAR(flood.contour.max_um, quiet.contour.max_um, 1e-9) << "max contour error, um";
  EXPECT_NEAR(flood.contour.mean_um, quiet.contour.mean_um, 1e-9) << "mean contour error, um";
  EXPECT_NEAR(flood.contour.std_um, quiet.contour.std_um, 1e-9) << "std of the contour error, um";

  EXPECT_GT(flood.load, 0.99) << "the flood did not saturate the wire";
  EXPECT_LT(quiet.load, 0.2) << "telemetry alone";
  const double offered_per_s = static_cast<double>(flood.flood_frames) / flood.motion_s;
  EXPECT_GT(offered_per_s, 9000.0) << "flood frames per second";
  EXPECT_GT(flood.node.rx_ignored, 0u);
  EXPECT_GT(flood.node.rx_malformed, 0u);
  EXPECT_EQ(flood.rx_fifo_overflows, 0u) << "the node's receive FIFO overflowed: frames lost unread";
  EXPECT_GT(flood.node.tx_dropped, 0u) << "a saturated bus must cost the node frames, and they must be counted";
  EXPECT_EQ(quiet.node.tx_dropped, 0u);
  EXPECT_TRUE(flood.tx_dropped_flag_seen) << "no heartbeat with tx_dropped after the flood";

  RecordProperty("flood_frames_per_s", static_cast<int>(offered_per_s));
  RecordProperty("bus_load_permille", static_cast<int>(flood.load * 1000.0));
  RecordProperty("node_tx_dropped", static_cast<int>(flood.node.tx_dropped));
  RecordProperty("node_tx_frames", static_cast<int>(flood.node.tx_frames));
  RecordProperty("node_rx_frames", static_cast<int>(flood.node.rx_frames));
  RecordProperty("node_rx_ignored", static_cast<int>(flood.node.rx_ignored));
  RecordProperty("node_rx_malformed", static_cast<int>(flood.node.rx_malformed));
  RecordProperty("contour_max_nm", static_cast<int>(flood.contour.max_um * 1000.0));
}

TEST(BusFlood, AnEstopSentIntoTheFloodMakesTheOutputsSafeOnTheNextTick) {
  const CircleRun r = run_circle("estop", true, 5000);
  ASSERT_GE(r.estop_sent_tick, 0) << "the circle never reached the e-stop point";
  ASSERT_GE(r.estop_arrival_tick, 0) << "the e-stop never reached the node";
  ASSERT_GE(r.estop_safe_tick, 0) << "the outputs never went safe";
  EXPECT_EQ(r.rx_fifo_overflows, 0u) << "frames lost in the node's receive FIFO";
  EXPECT_LE(r.estop_frames_ahead, kBacklog);
  // The emulated bus has two sides, so the e-stop queues behind the flooding
  // host's own backlog (at most kBacklog frames of <= 131 bits: 4 ms); on a
  // real bus a separate flooder loses the next arbitration to it (id 0x001).
  EXPECT_LE(r.estop_arrival_tick - r.estop_sent_tick, 4) << "ticks from sending to arrival behind the flood backlog";
  EXPECT_LE(r.estop_safe_tick - r.estop_arrival_tick, 1) << "ticks from arrival to safe outputs";
  EXPECT_EQ(r.missed_ticks, 0u);
  RecordProperty("estop_send_to_arrival_ticks", static_cast<int>(r.estop_arrival_tick - r.estop_sent_tick));
  RecordProperty("estop_arrival_to_safe_ticks", static_cast<int>(r.estop_safe_tick - r.estop_arrival_tick));
}

// The most frames the wire can carry, all for other nodes: the node must
// read them as fast as they come (kMaxRxPerService per tick) or its receive
// FIFO overflows, and an e-stop could be among the frames lost.
TEST(BusFlood, TheShortestFramesAtFullLoadOverflowNoReceiveFifoAndTheEstopGetsThrough) {
  const CircleRun r = run_circle("shortest", true, 5000, true);
  ASSERT_GE(r.estop_safe_tick, 0) << "the outputs never went safe";
  EXPECT_GT(r.load, 0.99);
  EXPECT_GT(static_cast<double>(r.flood_frames) / r.motion_s, 20'000.0) << "flood frames per second";
  EXPECT_EQ(r.rx_fifo_overflows, 0u) << "frames lost unread in the node's receive FIFO";
  EXPECT_LE(r.estop_safe_tick - r.estop_arrival_tick, 1) << "ticks from arrival to safe outputs";
  EXPECT_EQ(r.missed_ticks, 0u);
  RecordProperty("flood_frames_per_s", static_cast<int>(static_cast<double>(r.flood_frames) / r.motion_s));
  RecordProperty("rx_fifo_overflows", static_cast<int>(r.rx_fifo_overflows));
}

}  // namespace
}  // namespace tnv
