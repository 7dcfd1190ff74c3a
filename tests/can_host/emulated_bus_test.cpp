// The emulated controller: the real firmware node behind the virtual bus,
// in simulated time, with its parameters in a file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "firmware/can/param_table.hpp"
#include "hal/axis.hpp"
#include "tools/can/node_client.hpp"
#include "tools/can/telemetry_view.hpp"
#include "tools/can_emu/emulated_bus.hpp"

namespace tnv {
namespace {

namespace can = fw::can;
using can_host::EmulatedBus;
using can_host::Micros;
using can_host::NodeClient;

std::string temp_path(const std::string& name) {
  std::string file = "tnvctl_";
  file.append(std::to_string(::getpid())).append("_").append(name);
  const auto p = std::filesystem::temp_directory_path() / file;
  std::filesystem::remove(p);
  return p.string();
}

std::unique_ptr<EmulatedBus> make_bus(const std::string& storage, std::uint8_t node = 1) {
  can_host::EmulatedNodeOptions o;
  o.storage_path = storage;
  o.node = node;
  std::string error;
  auto bus = EmulatedBus::create(o, error);
  EXPECT_TRUE(bus) << error;
  return bus;
}

const can::ParamDef& param(const char* name) { return *can::find_param(name); }

TEST(EmulatedBus, ARequestIsAnsweredWithinAFewSimulatedMilliseconds) {
  const std::string storage = temp_path("answer.params");
  auto bus = make_bus(storage);
  NodeClient client(*bus, 1);
  const Micros t0 = bus->now();
  EXPECT_EQ(client.get(param("x.sliding.gamma")), static_cast<double>(0.4155f));
  const Micros took = bus->now() - t0;
  EXPECT_GE(took.count(), 1000) << "the node answers in service(), after a tick";
  EXPECT_LE(took.count(), 3000) << "took " << took.count() << " us";
  EXPECT_EQ(client.set(param("x.sliding.gamma"), 0.25), 0.25);
  EXPECT_EQ(bus->node().settings().firmware.axis[0].sliding.gamma, 0.25);
  EXPECT_FALSE(std::filesystem::exists(storage)) << "nothing is saved until save_params";
}

TEST(EmulatedBus, ABurstOfCaptureFramesTakesTheTimeTheWireNeeds) {
  auto bus = make_bus(temp_path("burst.params"));
  NodeClient client(*bus, 1);
  client.set(param("capture.trigger"), 0);  // immediate
  client.capture(can::CaptureOp::arm);
  client.pump(Micros{300'000});
  const can_host::CaptureStatus status = client.capture(can::CaptureOp::abort);
  ASSERT_GT(status.image_bytes(), 255u * 7u);
  client.set(param("tlm.position_ms"), 0);  // only the upload on the wire
  client.set(param("tlm.heartbeat_ms"), 0);
  bus->send(can_host::capture_request(1, 0x11 /* host 1, sequence 1 */, can::CaptureOp::upload, 255, 0));
  const Micros t0 = bus->now();
  int frames = 0;
  Micros last{0};
  while (frames < 255) {
    const auto f = bus->receive(Micros{100'000});
    ASSERT_TRUE(f) << "after " << frames << " frames";
    if (can::message_of(f->id) == static_cast<std::uint8_t>(can::MessageId::capture_data)) {
      ++frames;
      last = bus->now();
    }
  }
  const double took_ms = static_cast<double>((last - t0).count()) / 1000.0;
  EXPECT_GE(took_ms, 255 * 0.111) << "faster than 1 Mbit/s allows";
  EXPECT_LE(took_ms, 255 * 0.111 + 3.0) << "the node should keep the wire busy";
}

TEST(EmulatedBus, ACaptureUploadWithALostFrameStillEqualsTheNodesBuffer) {
  auto bus = make_bus(temp_path("lost.params"));
  NodeClient client(*bus, 1);
  client.set(param("capture.trigger"), 0);
  client.set(param("capture.channels"), 0b11);  // pos_x, pos_y
  client.capture(can::CaptureOp::arm);
  client.pump(Micros{500'000});
  const can_host::CaptureStatus status = client.capture(can::CaptureOp::abort);
  ASSERT_EQ(status.state, can::CaptureState::done);
  ASSERT_GT(status.image_bytes(), 300u * 7u);
  int data_frames = 0;
  bus->set_node_tx_filter([&data_frames](const hal::CanFrame& f) {
    if (can::message_of(f.id) != static_cast<std::uint8_t>(can::MessageId::capture_data)) return true;
    return ++data_frames != 300;  // the 300th data frame is lost on the wire (block 2, frame 44)
  });
  const std::vector<std::uint8_t> image = client.upload(status);
  EXPECT_EQ(client.upload_rerequests(), 1u);
  const auto words = bus->node().capture_words();
  ASSERT_EQ(image.size(), words.size() * 4);
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::uint32_t got = image[4 * i] | image[4 * i + 1] << 8 | image[4 * i + 2] << 16 |
                              static_cast<std::uint32_t>(image[4 * i + 3]) << 24;
    ASSERT_EQ(got, words[i]) << "word " << i;
  }
}

TEST(EmulatedBus, SavedParametersAreLoadedAtTheNextStartAndADamagedFileIsReported) {
  const std::string storage = temp_path("saved.params");
  {
    auto bus = make_bus(storage);
    NodeClient client(*bus, 1);
    client.set(param("x.sliding.gamma"), 0.25);
    client.command(can::CommandCode::save_params);
    EXPECT_TRUE(std::filesystem::exists(storage));
    EXPECT_FALSE(std::filesystem::exists(storage + ".tmp")) << "written to a temp file, then renamed";
  }
  {
    auto bus = make_bus(storage);
    EXPECT_EQ(bus->startup_note(), "");
    NodeClient client(*bus, 1);
    EXPECT_EQ(client.get(param("x.sliding.gamma")), 0.25);
  }
  {
    std::fstream f(storage, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(20);
    f.put('\x5A');
  }
  auto bus = make_bus(storage);
  EXPECT_NE(bus->startup_note().find("storage_corrupt"), std::string::npos) << bus->startup_note();
  NodeClient client(*bus, 1);
  EXPECT_EQ(client.get(param("x.sliding.gamma")), static_cast<double>(0.4155f)) << "defaults, nothing half-loaded";
  EXPECT_TRUE(bus->node().storage_fault());
  std::filesystem::remove(storage);
}

TEST(EmulatedBus, TheTelemetryStreamDecodesAtTheConfiguredRates) {
  auto bus = make_bus(temp_path("telemetry.params"));
  NodeClient client(*bus, 1);
  for (const char* p : {"tlm.sliding_ms", "tlm.output_ms", "tlm.contour_ms", "tlm.arsc_ms"}) client.set(param(p), 10);
  can_host::TelemetryView view;
  client.set_listener([&view](const hal::CanFrame& f, can::MessageId id) { view.take(f, id); });
  client.pump(Micros{1'000'000});
  // 100 ms heartbeat; every 10 ms per axis a position and a sliding frame (8 bytes) and a DAC frame (2
  // bytes), and the force (4 bytes), contour and arsc frames (8 bytes).
  const double axes = static_cast<double>(hal::kAxisCount);
  const double frames = static_cast<double>(view.frames);
  EXPECT_NEAR(frames, 10 + (3 * axes + 3) * 100, 8) << "frames in 1 s";
  const double bits_per_10ms = 2 * axes * 111 + axes * 63 + 79 + 2 * 111;  // 47 + 8 x bytes each
  EXPECT_NEAR(static_cast<double>(view.bits), 10 * 111 + 100 * bits_per_10ms, 8 * 111) << "bits in 1 s";
  ASSERT_TRUE(view.heartbeat && view.position_mm && view.following_mm && view.s_mm_s && view.output && view.contour &&
              view.arsc);
  EXPECT_EQ(view.arsc->feed_override, 1.0) << "no program: the motion core's override at rest";
  EXPECT_EQ(view.arsc->force_ref_n, 0.0) << "the force loop is off";
  EXPECT_EQ(view.heartbeat->state, fw::MotionState::disabled);
  // The emulated table powers up at the circle's start (R, 0) = (6, 0) mm, read to the encoder count.
  EXPECT_NEAR((*view.position_mm)[0], 6.0, 0.5e-3) << "x, mm";
  EXPECT_NEAR((*view.position_mm)[1], 0.0, 0.5e-3) << "y, mm";
  EXPECT_EQ(view.contour->motion_tick, -1.0) << "no motion";
  EXPECT_EQ(view.contour->contour_um, 0.0);
}

TEST(EmulatedBus, AFreshNodeTakesTheRequestedIdAStoredOneKeepsItsOwn) {
  const std::string storage = temp_path("id.params");
  {
    auto bus = make_bus(storage, 7);
    EXPECT_EQ(bus->node_id(), 7);
    NodeClient client(*bus, 7);
    client.set(param("can.node_id"), 9);  // applies at the next start
    client.command(can::CommandCode::save_params);
  }
  auto bus = make_bus(storage, 7);
  EXPECT_EQ(bus->node_id(), 9);
  std::filesystem::remove(storage);
}

}  // namespace
}  // namespace tnv
