// Shaper designs off the real-time thread: a parameter change whose design
// the node lacks is designed on the worker and the request handled again
// when it is done (answered once, on the state of that moment); the
// defaults' designs and the designs a load made are at hand, so
// restore_defaults and load cost a copy (docs/safety.md "Real-time budget").
#include <gtest/gtest.h>

#include "drivers/storage/stepped_storage_worker.hpp"
#include "firmware/tick/work_meter.hpp"
#include "tests/firmware/can/node_bench.hpp"

namespace tnv::test {
namespace {

using fw::can::CommandCode;
using fw::can::ErrorCode;
using fw::can::MessageId;
using fw::can::ParamOp;

// Runs a posted job only when the test says so (run_pending()).
using StepWorker = drivers::SteppedStorageWorker;

hal::CanFrame shaper(std::uint8_t axis, fw::ShaperType type, double freq_hz, double zeta = 0.05) {
  hal::CanFrame f = frame_to(MessageId::shaper, kNode);
  set_raw(f, MessageId::shaper, "axis", axis);
  set_raw(f, MessageId::shaper, "type", static_cast<std::uint32_t>(type));
  set_value(f, MessageId::shaper, "zeta", zeta);
  set_value(f, MessageId::shaper, "freq", freq_hz);
  return f;
}

ErrorCode ack(const hal::CanFrame& r) { return static_cast<ErrorCode>(raw_of(r, MessageId::command_ack, "result")); }

// Blocks of firmware code one service() runs (0 when the build is not metered).
std::uint64_t service_blocks(NodeBench& b) {
  const std::uint64_t before = fw::work_blocks();
  b.node->service();
  return fw::work_blocks() - before;
}

// 50 us of board time at the rig's 5 ns per block (docs/safety.md "Charged time").
// The asan tree's clang at -O1 runs more blocks for the same code: a
// restore_defaults there took 14,113, and the cheapest design (mzv) about
// 17,000 more (zvdd 154,000), so 25,000 still tells a design in service()
// from none.
#if defined(__SANITIZE_ADDRESS__) && defined(__clang__)
constexpr std::uint64_t kBudgetBlocks = 25'000;
#else
constexpr std::uint64_t kBudgetBlocks = 10'000;
#endif

TEST(CanNodeShaperDesign, ANewSpecIsDesignedOnTheWorkerAndAnsweredOnceWhenDone) {
  StepWorker worker;
  NodeBench b(quiet_settings(), false, &worker);
  const fw::ShaperSpec before = b.node->settings().shaper[0].spec;
  hal::CanFrame f = shaper(0, fw::ShaperType::zvdd, 41.25);
  f.data[0] = 0x13;  // host 1, sequence 3: the late answer must echo it
  EXPECT_TRUE(b.request(f).empty()) << "no answer before the design is made";
  EXPECT_TRUE(b.node->design_in_flight());
  EXPECT_FALSE(worker.idle()) << "a design job posted";
  EXPECT_TRUE(fw::same_spec(b.node->settings().shaper[0].spec, before)) << "nothing applied yet";

  // Meanwhile every other change waits: the design is for the set as it was.
  const std::uint16_t eta = id_of("x.sliding.eta_mm_s");
  const hal::CanFrame set = b.reply(param_request(kNode, ParamOp::set, eta, fw::can::to_wire(NodeBench::find("x.sliding.eta_mm_s"), 2.0)));
  EXPECT_EQ(static_cast<ErrorCode>(raw_of(set, MessageId::param_reply, "result")), ErrorCode::busy);
  EXPECT_EQ(ack(b.reply(command(kNode, CommandCode::save_params))), ErrorCode::busy);
  EXPECT_EQ(ack(b.reply(command(kNode, CommandCode::restore_defaults))), ErrorCode::busy);

  ASSERT_TRUE(worker.run_pending());
  const std::vector<hal::CanFrame> out = b.request(hal::CanFrame{0x7FF, false, 0, {}});  // a foreign frame: just a service()
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(is(out[0], MessageId::command_ack));
  EXPECT_EQ(raw_of(out[0], MessageId::command_ack, "request"), static_cast<std::uint32_t>(MessageId::shaper));
  EXPECT_EQ(raw_of(out[0], MessageId::command_ack, "tag"), 0x13u);
  EXPECT_EQ(ack(out[0]), ErrorCode::ok);
  EXPECT_FALSE(b.node->design_in_flight());
  EXPECT_EQ(b.node->settings().shaper[0].spec.type, fw::ShaperType::zvdd);
  EXPECT_FLOAT_EQ(static_cast<float>(b.node->settings().shaper[0].spec.mode.freq_hz), 41.25f);

  // The same spec again is at hand: answered at once, no job.
  EXPECT_EQ(ack(b.reply(shaper(0, fw::ShaperType::zvdd, 41.25))), ErrorCode::ok);
  EXPECT_EQ(worker.jobs_run(), 1u) << "no second job";
}

TEST(CanNodeShaperDesign, TheRequestIsCheckedAgainOnTheStateWhenItsDesignIsDone) {
  StepWorker worker;
  NodeBench b(quiet_settings(), false, &worker);
  const fw::ShaperSpec before = b.node->settings().shaper[1].spec;
  EXPECT_TRUE(b.request(shaper(1, fw::ShaperType::ei, 27.5)).empty());
  // The host gives up command ownership before the design is done.
  EXPECT_EQ(ack(b.reply(command(kNode, CommandCode::release_ownership))), ErrorCode::ok);
  ASSERT_TRUE(worker.run_pending());
  const std::vector<hal::CanFrame> out = b.request(hal::CanFrame{0x7FF, false, 0, {}});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(ack(out[0]), ErrorCode::not_owner);
  EXPECT_TRUE(fw::same_spec(b.node->settings().shaper[1].spec, before));
}

TEST(CanNodeShaperDesign, ACommitWithANewSpecIsAnsweredWithItsCountAfterTheDesign) {
  StepWorker worker;
  NodeBench b(quiet_settings(), false, &worker);
  const std::uint16_t freq = id_of("x.shaper.freq_hz");
  const hal::CanFrame staged =
      b.reply(param_request(kNode, ParamOp::stage, freq, fw::can::to_wire(NodeBench::find("x.shaper.freq_hz"), 33.0)));
  EXPECT_EQ(static_cast<ErrorCode>(raw_of(staged, MessageId::param_reply, "result")), ErrorCode::ok);
  EXPECT_TRUE(b.request(param_request(kNode, ParamOp::commit, 0)).empty());
  EXPECT_EQ(b.node->staged_count(), 1u) << "the staged set stays until the commit is answered";
  ASSERT_TRUE(worker.run_pending());
  const std::vector<hal::CanFrame> out = b.request(hal::CanFrame{0x7FF, false, 0, {}});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(static_cast<ErrorCode>(raw_of(out[0], MessageId::param_reply, "result")), ErrorCode::ok);
  EXPECT_EQ(raw_of(out[0], MessageId::param_reply, "param"), 1u) << "one parameter applied";
  EXPECT_EQ(b.node->staged_count(), 0u);
  EXPECT_DOUBLE_EQ(b.param("x.shaper.freq_hz"), 33.0);
}

TEST(CanNodeShaperDesign, RestoreDefaultsAndALoadNeedNoDesignInService) {
  if (!fw::work_meter_enabled()) GTEST_SKIP() << "the firmware is built without the work meter";
  StepWorker worker;
  NodeBench b(quiet_settings(), false, &worker);
  // A spec of its own, saved.
  EXPECT_TRUE(b.request(shaper(0, fw::ShaperType::mzv, 52.0)).empty());
  ASSERT_TRUE(worker.run_pending());
  EXPECT_EQ(b.port.drain().size(), 0u);
  b.node->service();
  ASSERT_EQ(ack(b.port.drain().at(0)), ErrorCode::ok);
  b.port.send(command(kNode, CommandCode::save_params));
  b.node->service();
  ASSERT_TRUE(worker.run_pending());
  b.node->service();
  ASSERT_EQ(ack(b.port.drain().at(0)), ErrorCode::ok);

  // Back to the defaults: their designs were made at construction.
  b.port.send(command(kNode, CommandCode::restore_defaults));
  const std::uint64_t restore = service_blocks(b);
  ASSERT_EQ(ack(b.port.drain().at(0)), ErrorCode::ok);
  EXPECT_EQ(b.node->settings().shaper[0].spec.type, quiet_settings().shaper[0].spec.type);
  EXPECT_LT(restore, kBudgetBlocks) << "restore_defaults designed a shaper in service()";

  // The load's job designed the saved spec on the worker: applying it is a copy.
  b.port.send(command(kNode, CommandCode::load_params));
  b.node->service();
  ASSERT_TRUE(worker.run_pending());
  const std::uint64_t applied = service_blocks(b);
  ASSERT_EQ(ack(b.port.drain().at(0)), ErrorCode::ok);
  EXPECT_EQ(b.node->settings().shaper[0].spec.type, fw::ShaperType::mzv);
  EXPECT_FALSE(b.node->design_in_flight());
  EXPECT_EQ(worker.jobs_run(), 3u) << "design, save, load: no second design job";
  EXPECT_LT(applied, kBudgetBlocks) << "the load's answer designed a shaper in service()";
}

}  // namespace
}  // namespace tnv::test
