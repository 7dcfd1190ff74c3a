// Charged time on the HIL rig: the emulated board's clock does not wait
// for a slow firmware call. A call over the threshold shows as missed
// ticks, a longer one as a watchdog trip; every normal call charges nothing.
// Work is metered in basic blocks of firmware code (work_meter.hpp), so a
// slow call here is firmware code doing a lot, not a busy host.
#include <gtest/gtest.h>

#include "emulator/scenario_file.hpp"
#include "tests/hil/can_node_rig.hpp"
#include "firmware/shaper/shaper_design.hpp"
#include "firmware/tick/work_meter.hpp"
#include "tools/hil/hil_rig.hpp"

namespace tnv::test {
namespace {

using fw::can::CommandCode;
using fw::can::MessageId;

// Runs firmware code (shaper designs) until the work meter has counted
// `board_ns` of modelled board time at the rig's default cost per block.
void burn_board_ns(std::int64_t board_ns) {
  const double blocks = static_cast<double>(board_ns) / hil::ChargeOptions{}.ns_per_block;
  const std::uint64_t start = fw::work_blocks();
  fw::ShaperSpec spec;
  spec.type = fw::ShaperType::zvdd;
  spec.mode = {30.0, 0.05};
  while (static_cast<double>(fw::work_blocks() - start) < blocks) {
    const fw::ShaperDesign d = fw::design_shaper(spec, 1e-3);
    if (d.taps.span() == 0) break;
  }
}

// A build for a board (TNV_WORK_METER=OFF) meters nothing, so charges nothing.
#define SKIP_WITHOUT_METER() \
  if (!fw::work_meter_enabled()) GTEST_SKIP() << "built with TNV_WORK_METER=OFF: nothing is metered"

// Without the meter an [io] run lands its writes with no firmware work
// before them: the build says so (tnv-hil warns and marks its JSON).
TEST(ChargedTime, AnIoScenarioIsFlaggedUnmeteredOnlyWithoutTheMeter) {
  const emu::ScenarioResult bench = emu::resolve_scenario("bench-no-cut");
  const emu::ScenarioResult plain = emu::resolve_scenario("no-cut");
  ASSERT_TRUE(bench.scenario && plain.scenario);
  ASSERT_TRUE(bench.scenario->io.enabled()) << "the bench profile has the SPI transport";
  EXPECT_EQ(hil::io_work_unmetered(*bench.scenario), !fw::work_meter_enabled());
  EXPECT_FALSE(hil::io_work_unmetered(*plain.scenario)) << "no [io]: nothing depends on the meter";
}

TEST(ChargedTime, TheWorkMeterCountsFirmwareCodeOnly) {
  SKIP_WITHOUT_METER();
  std::uint64_t start = fw::work_blocks();
  double host_sum = 0.0;
  for (int i = 0; i < 1000; ++i) host_sum += static_cast<double>(i);  // test code: not metered
  EXPECT_EQ(fw::work_blocks(), start);
  EXPECT_GT(host_sum, 0.0);
  burn_board_ns(1'000'000);
  EXPECT_GE(static_cast<double>(fw::work_blocks() - start), 1e6 / hil::ChargeOptions{}.ns_per_block);
}

std::unique_ptr<CanRig> holding_charged_rig() {
  auto r = CanRig::make();
  if (!r || r->result(command(kRigNode, CommandCode::enable)) != kOk) return nullptr;
  if (!r->run_until(fw::MotionState::holding, 10)) return nullptr;
  for (int k = 0; k < 20; ++k) r->step();
  return r;
}

TEST(ChargedTime, TheWholeNoCutCircleChargesNothing) {
  const emu::Scenario scenario = *emu::builtin_scenario("no-cut");
  std::string error;
  auto rig = hil::HilRig::create(scenario, fw::default_firmware_config(), fw::ControllerKind::rdvsc, error);
  ASSERT_TRUE(rig) << error;
  rig->home();
  ASSERT_EQ(rig->task.start_circle(hil::circle_spec_for(scenario)), fw::CommandStatus::ok);
  for (int k = 0; k < 25'000 && rig->task.moving(); ++k) rig->tick();
  ASSERT_FALSE(rig->task.moving());
  EXPECT_GT(rig->charged().calls, 19'000u);  // 19.45 s of circle, one call per tick
  EXPECT_EQ(rig->charged().charged_calls, 0u);
  EXPECT_EQ(rig->charged().charged_ns, 0);
  EXPECT_LT(rig->charged().max_call_ns, rig->charging.threshold_ns);
  EXPECT_EQ(rig->task.counters().missed_ticks, 0u);
  EXPECT_EQ(rig->task.counters().late_ticks, 0u);
}

TEST(ChargedTime, ASlowCallShowsAsMissedTicks) {
  SKIP_WITHOUT_METER();
  auto r = holding_charged_rig();
  ASSERT_TRUE(r);
  ASSERT_EQ(r->task().counters().missed_ticks, 0u);
  r->rig->charged_call([] { burn_board_ns(2'500'000); });  // 2.5 ms in one call of the loop
  for (int k = 0; k < 5; ++k) r->step();
  EXPECT_EQ(r->rig->charged().charged_calls, 1u);
  EXPECT_GE(r->task().counters().missed_ticks, 2u);
  EXPECT_LE(r->task().counters().missed_ticks, 3u);
  EXPECT_FALSE(r->task().fault().active()) << "2 lost ticks are within the supervisor's limit";
}

TEST(ChargedTime, WithoutChargingTheSameCallIsInvisible) {
  SKIP_WITHOUT_METER();
  auto r = holding_charged_rig();
  ASSERT_TRUE(r);
  r->rig->charging.enabled = false;
  r->rig->charged_call([] { burn_board_ns(2'500'000); });
  for (int k = 0; k < 5; ++k) r->step();
  EXPECT_EQ(r->task().counters().missed_ticks, 0u);
}

TEST(ChargedTime, ACallLongerThanTheWatchdogTimeoutTripsTheBoard) {
  SKIP_WITHOUT_METER();
  auto r = holding_charged_rig();
  ASSERT_TRUE(r);
  r->rig->charged_call([] { burn_board_ns(5'000'000); });  // the board watchdog's timeout is 3 ms
  r->step();
  EXPECT_TRUE(r->rig->machine.board_outputs().watchdog_tripped);
  EXPECT_TRUE(r->task().fault().active());
  EXPECT_GE(r->task().counters().missed_ticks, 4u);
}

// A storage whose write runs 4 ms of firmware work, as slow flash code would.
class SlowStorage final : public hal::ParamStorage {
 public:
  hal::HalStatus write(std::span<const std::uint8_t> image) noexcept override {
    burn_board_ns(4'000'000);
    return inner.write(image);
  }
  hal::HalStatus read(std::span<std::uint8_t> out, std::size_t& size) noexcept override { return inner.read(out, size); }
  MemoryStorage inner;
};

// A holding node on its own rig with the slow storage, with or without the storage worker.
struct SlowStorageBench {
  explicit SlowStorageBench(bool with_worker) {
    const emu::Scenario scenario = *emu::builtin_scenario("no-cut");
    std::string error;
    rig = hil::HilRig::create(scenario, fw::default_firmware_config(), fw::ControllerKind::rdvsc, error);
    rig->home();
    fw::can::NodeSettings s = fw::can::default_node_settings();
    s.firmware = rig->task.config();
    s.telemetry = {0, 0, 0, 0, 0, 0, 0};
    node = std::make_unique<fw::can::CanNode>(rig->task, port, storage, s, false, nullptr,
                                              with_worker ? &worker : nullptr);
    port.send(command(kRigNode, CommandCode::take_ownership));
    port.send(command(kRigNode, CommandCode::enable));
    for (int k = 0; k < 20; ++k) step();
    port.drain();
  }
  void step() {
    rig->tick();
    rig->charged_call([this]() noexcept { node->service(); });
    worker.run_pending();  // outside the charged time
  }
  std::unique_ptr<hil::HilRig> rig;
  FakeCanPort port;
  SlowStorage storage;
  drivers::SteppedStorageWorker worker;
  std::unique_ptr<fw::can::CanNode> node;
};

TEST(ChargedTime, ASlowSaveInTheServiceTripsTheBoardAndOnTheWorkerCostsNothing) {
  SKIP_WITHOUT_METER();
  for (const bool with_worker : {false, true}) {
    SCOPED_TRACE(with_worker ? "storage worker" : "save in service()");
    SlowStorageBench b(with_worker);
    ASSERT_EQ(b.rig->task.state(), fw::MotionState::holding);
    b.port.send(command(kRigNode, CommandCode::save_params));
    std::vector<hal::CanFrame> acks;
    for (int k = 0; k < 10 && acks.empty(); ++k) {
      b.step();
      acks = only(b.port.drain(), MessageId::command_ack);
    }
    ASSERT_EQ(acks.size(), 1u);
    EXPECT_EQ(raw_of(acks[0], MessageId::command_ack, "code"), static_cast<std::uint32_t>(CommandCode::save_params));
    EXPECT_EQ(b.storage.inner.writes, 1);
    for (int k = 0; k < 5; ++k) b.step();
    if (with_worker) {
      EXPECT_EQ(raw_of(acks[0], MessageId::command_ack, "result"), kOk);
      EXPECT_EQ(b.rig->task.counters().missed_ticks, 0u);
      EXPECT_FALSE(b.rig->task.fault().active());
      EXPECT_EQ(b.rig->charged().charged_calls, 0u);
      EXPECT_EQ(b.worker.jobs_run(), 1u);
    } else {
      EXPECT_EQ(b.rig->charged().charged_calls, 1u);
      EXPECT_GE(b.rig->task.counters().missed_ticks, 4u);
      EXPECT_TRUE(b.rig->machine.board_outputs().watchdog_tripped);
      EXPECT_TRUE(b.rig->task.fault().active());
    }
  }
}

}  // namespace
}  // namespace tnv::test
