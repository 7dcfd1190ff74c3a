// EXCITE over CAN (issue 7): the frame's round trip through the table
// codec, every malformed or refused request answered with its error and
// nothing changed, the capture of an excitation aligned to its first
// tick, and an autotune parameter set the node refuses leaving every
// parameter as it was.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "firmware/can/capture_channels.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/param_table.hpp"
#include "firmware/io/dac_code.hpp"
#include "tools/can/autotune_plan.hpp"
#include "tools/can/can_identify.hpp"
#include "tools/can/node_client.hpp"
#include "tools/can_emu/emulated_bus.hpp"

namespace tnv::excite_message_test {
namespace {

namespace can = fw::can;
namespace fields = fw::can::fields;
using can_host::CommandAck;
using can_host::EmulatedBus;
using can_host::Micros;
using can_host::NodeClient;

std::string excite_storage(const std::string& name) {
  std::string file = "tnvctl_excite_";
  file.append(std::to_string(::getpid())).append("_").append(name);
  const auto p = std::filesystem::temp_directory_path() / file;
  std::filesystem::remove(p);
  return p.string();
}

std::unique_ptr<EmulatedBus> excite_bus(const std::string& name) {
  can_host::EmulatedNodeOptions o;
  o.storage_path = excite_storage(name);
  std::string error;
  auto bus = EmulatedBus::create(o, error);
  EXPECT_TRUE(bus) << error;
  return bus;
}

// Sends a raw frame and returns the COMMAND_ACK that answers EXCITE.
CommandAck excite_ack(EmulatedBus& bus, const hal::CanFrame& frame) {
  bus.send(frame);
  const Micros deadline = bus.now() + Micros{250'000};
  while (bus.now() < deadline) {
    const std::optional<hal::CanFrame> f = bus.receive(deadline - bus.now());
    if (!f) continue;
    const can::MessageDef* m = can::classify(*f);
    if (m == nullptr || m->id != fields::kAckMsg.id) continue;
    const CommandAck a = can_host::read_command_ack(*f);
    if (a.request == fields::kExciteMsg.id) return a;
  }
  ADD_FAILURE() << "no COMMAND_ACK to EXCITE within 250 ms";
  return {};
}

hal::CanFrame excite_frame(std::uint8_t axis, std::uint8_t kind, double level_mm_s, double duration_s) {
  return can_host::excite_request(1, 0x11 /* host 1, sequence 1 */, axis, kind, level_mm_s, duration_s);
}

TEST(ExciteMessage, FrameRoundTripsThroughTheTableCodec) {
  const hal::CanFrame f = excite_frame(1, 1, -12.5, 5.0);
  ASSERT_EQ(can::classify(f), &fields::kExciteMsg);
  EXPECT_EQ(f.dlc, 8);
  EXPECT_EQ(can::read_raw(f, fields::kExciteAxis), 1u);
  EXPECT_EQ(can::read_raw(f, fields::kExciteKind), 1u);
  EXPECT_DOUBLE_EQ(can::read(f, fields::kExciteDuration), 5.0) << "s";
  EXPECT_DOUBLE_EQ(can::read(f, fields::kExciteLevel), -12.5) << "mm/s";
  // 1 ms resolution of the duration: 0.15 s is 150 ms exactly.
  EXPECT_EQ(can::read_raw(excite_frame(0, 0, 10.0, 0.15), fields::kExciteDuration), 150u);
  // A duration the u16 cannot carry is sent as 0 s, which the node refuses.
  EXPECT_EQ(can::read_raw(excite_frame(0, 0, 10.0, 100.0), fields::kExciteDuration), 0u);
}

TEST(ExciteMessage, MalformedAndRefusedRequestsChangeNothing) {
  auto bus = excite_bus("refused");
  ASSERT_TRUE(bus);
  NodeClient client(*bus, 1);
  const can::ParamDef& eta = *can::find_param("x.sliding.eta_mm_s");
  const double eta_before = client.get(eta);
  client.take_ownership();  // host 1: the raw frames below carry its tag too

  // Disabled: start_excitation needs holding.
  CommandAck a = excite_ack(*bus, excite_frame(0, 0, 10.0, 0.15));
  EXPECT_EQ(a.result, can::ErrorCode::busy);
  EXPECT_EQ(a.state, fw::MotionState::disabled);

  client.command(can::CommandCode::enable);
  client.pump(Micros{100'000});
  const double x0_mm = bus->rig().task.last_record().axis[0].position_mm;

  struct Bad {
    const char* what;
    hal::CanFrame frame;
    can::ErrorCode expected;
    const can::FieldDef* field;  // the field COMMAND_ACK.detail names (nullptr: 0)
  };
  hal::CanFrame short_frame = excite_frame(0, 0, 10.0, 0.15);
  short_frame.dlc = 7;
  std::vector<Bad> cases{
      {"7-byte frame", short_frame, can::ErrorCode::bad_length, nullptr},
      // level is i16 at 0.01 mm/s: NaN goes out as 0, infinity as the largest code; both refused.
      {"NaN level", excite_frame(0, 0, std::numeric_limits<double>::quiet_NaN(), 0.15), can::ErrorCode::out_of_range,
       &fields::kExciteLevel},
      {"infinite level", excite_frame(0, 0, std::numeric_limits<double>::infinity(), 0.15),
       can::ErrorCode::out_of_range, &fields::kExciteLevel},
      {"axis past the list", excite_frame(static_cast<std::uint8_t>(hal::kAxisCount), 0, 10.0, 0.15), can::ErrorCode::bad_axis, &fields::kExciteAxis},
      {"axis 255", excite_frame(255, 0, 10.0, 0.15), can::ErrorCode::bad_axis, &fields::kExciteAxis},
      {"kind 5", excite_frame(0, 5, 10.0, 0.15), can::ErrorCode::out_of_range, &fields::kExciteKind},
      // Sweep / multisine (issue 17): 0.1 .. 40 s; a multisine holds 2 periods of 1 / excite.f_min_hz (1 s).
      {"sweep 0.05 s", excite_frame(0, 2, 2.0, 0.05), can::ErrorCode::out_of_range, &fields::kExciteDuration},
      {"multisine 50 s", excite_frame(0, 3, 2.0, 50.0), can::ErrorCode::out_of_range, &fields::kExciteDuration},
      {"multisine 1.5 s", excite_frame(0, 3, 2.0, 1.5), can::ErrorCode::invalid, &fields::kExciteDuration},
      {"open multisine level 0", excite_frame(0, 4, 0.0, 5.0), can::ErrorCode::out_of_range, &fields::kExciteLevel},
      {"level 0", excite_frame(0, 0, 0.0, 0.15), can::ErrorCode::out_of_range, &fields::kExciteLevel},
      {"level 150 mm/s", excite_frame(0, 0, 150.0, 0.15), can::ErrorCode::out_of_range, &fields::kExciteLevel},
      {"duration 0 s", excite_frame(0, 0, 10.0, 0.0), can::ErrorCode::out_of_range, &fields::kExciteDuration},
      {"duration 20 s", excite_frame(0, 0, 10.0, 20.0), can::ErrorCode::out_of_range, &fields::kExciteDuration},
  };
  for (const Bad& c : cases) {
    const CommandAck ack = excite_ack(*bus, c.frame);
    EXPECT_EQ(ack.result, c.expected) << c.what << ": got " << can::to_string(ack.result);
    EXPECT_EQ(ack.detail, c.field == nullptr ? 0 : fields::index_of(fields::kExciteMsg, *c.field)) << c.what;
    EXPECT_EQ(ack.state, fw::MotionState::holding) << c.what;
    EXPECT_FALSE(bus->rig().task.exciting()) << c.what << " started an excitation";
  }
  client.pump(Micros{50'000});
  EXPECT_NEAR(bus->rig().task.last_record().axis[0].position_mm, x0_mm, 1e-3)
      << "x moved by " << (bus->rig().task.last_record().axis[0].position_mm - x0_mm) * 1e3 << " um";

  // While moving: busy, and the move goes on undisturbed.
  client.move(1, 2.0, 10.0);
  a = excite_ack(*bus, excite_frame(0, 0, 10.0, 0.15));
  EXPECT_EQ(a.result, can::ErrorCode::busy);
  EXPECT_FALSE(bus->rig().task.exciting());
  EXPECT_TRUE(bus->rig().task.moving()) << "the refused EXCITE stopped the move";
  client.wait_at_rest(Micros{5'000'000});

  // While an excitation runs: busy for a second one.
  a = excite_ack(*bus, excite_frame(0, 0, 10.0, 0.15));
  ASSERT_EQ(a.result, can::ErrorCode::ok);
  a = excite_ack(*bus, excite_frame(1, 0, 10.0, 0.15));
  EXPECT_EQ(a.result, can::ErrorCode::busy);
  client.pump(Micros{500'000});
  EXPECT_FALSE(bus->rig().task.exciting()) << "a 0.35 s excitation still running after 0.5 s";

  EXPECT_EQ(client.get(eta), eta_before) << "a refused EXCITE changed a parameter";
  EXPECT_GE(bus->node().counters().requests_refused, cases.size() + 3);
  std::filesystem::remove(bus->storage_path());
}

TEST(ExciteMessage, CaptureArmedForMotionRecordsTheExcitationFromItsFirstTick) {
  auto bus = excite_bus("capture");
  ASSERT_TRUE(bus);
  NodeClient client(*bus, 1);
  client.command(can::CommandCode::enable);
  client.stage(*can::find_param("capture.channels"), (1u << can::channel_bit("pos_x")) | (1u << can::channel_bit("dac_x")));
  client.stage(*can::find_param("capture.trigger"), 1);                      // motion
  client.stage(*can::find_param("capture.decimation"), 1);
  client.commit();
  client.pump(Micros{200'000});

  fw::ExcitationSpec step;
  step.level_mm_s = 10.0;
  step.duration_s = 0.15;
  fw::DacScale dac;
  dac.full_scale_mm_s = client.get(*can::find_param("x.hw.dac_full_scale_mm_s"));
  const can_host::ExcitationSeries s = can_host::run_excitation_over_can(client, hal::Axis::x, step, dac);
  // 150 ticks of drive, then the settle (200 ticks) and the tick that ends it.
  ASSERT_EQ(s.command_mm_s.size(), 351u);
  const double level = fw::dac_code_to_speed_mm_s(fw::speed_to_dac_code(10.0, dac), dac);
  for (std::size_t j = 0; j < 150; ++j) ASSERT_DOUBLE_EQ(s.command_mm_s[j], level) << "tick " << j << " mm/s";
  for (std::size_t j = 150; j < s.command_mm_s.size(); ++j)
    ASSERT_DOUBLE_EQ(s.command_mm_s[j], 0.0) << "tick " << j << " mm/s";
  EXPECT_GT(s.position_mm[150] - s.position_mm[0], 0.5) << "moved only " << s.position_mm[150] - s.position_mm[0]
                                                        << " mm in 0.15 s at 10 mm/s";
  EXPECT_EQ(bus->node().capture_state(), can::CaptureState::done);
  std::filesystem::remove(bus->storage_path());
}

TEST(ExciteMessage, AutotuneSetTheNodeRefusesLeavesEveryParameterAsItWas) {
  auto bus = excite_bus("autotune_refused");
  ASSERT_TRUE(bus);
  NodeClient client(*bus, 1);
  client.command(can::CommandCode::enable);
  client.pump(Micros{100'000});
  const tune::AxisIdentification id = can_host::identify_axis_over_can(client, hal::Axis::x);
  ASSERT_TRUE(id.ok) << id.error;
  tune::AxisDesign design = tune::design_axis(id);
  ASSERT_TRUE(design.ok) << design.error;
  // Break Theorem 2 (phi > eta/(q+1)) in the last sliding-mode value staged.
  design.sliding.phi_mm_s = 0.5 * design.sliding.eta_mm_s / (design.sliding.q + 1.0);
  const can_host::AxisPlan plan = can_host::plan_autotune(client, id, design);
  try {
    can_host::apply_changes(client, plan.changes);
    FAIL() << "the node accepted phi " << design.sliding.phi_mm_s << " mm/s below eta/(q+1)";
  } catch (const can_host::RequestError& e) {
    EXPECT_EQ(e.code(), can::ErrorCode::invalid) << e.what();
  }
  for (const can_host::ParamChange& c : plan.changes)
    EXPECT_EQ(client.get(*c.param), c.old_value) << c.param->name << " changed although the set was refused";
  EXPECT_EQ(bus->node().staged_count(), 0u) << "the refused set was left staged";
  std::filesystem::remove(bus->storage_path());
}

}  // namespace
}  // namespace tnv::excite_message_test
