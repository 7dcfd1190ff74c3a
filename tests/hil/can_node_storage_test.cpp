// save_params / load_params off the real-time thread: the node posts the
// job to the storage worker and answers in a later service(); while a job
// is in flight, conflicting requests are busy and nothing is half-applied.
// restore_defaults copies defaults computed once at construction.
#include <gtest/gtest.h>

#include "tests/hil/can_node_rig.hpp"

namespace tnv::test {
namespace {

using fw::can::CommandCode;
using fw::can::ErrorCode;
using fw::can::MessageId;
using fw::can::ParamOp;

constexpr auto kStorageBusy = static_cast<std::uint32_t>(ErrorCode::busy);

std::unique_ptr<CanRig> holding_for_storage() {
  auto r = CanRig::make();
  if (!r || r->result(command(kRigNode, CommandCode::enable)) != kOk) return nullptr;
  if (!r->run_until(fw::MotionState::holding, 10)) return nullptr;
  return r;
}

std::uint32_t storage_ack_result(const std::vector<hal::CanFrame>& out, CommandCode code) {
  const std::vector<hal::CanFrame> acks = only(out, MessageId::command_ack);
  if (acks.size() != 1 || raw_of(acks[0], MessageId::command_ack, "code") != static_cast<std::uint32_t>(code)) return 255;
  return raw_of(acks[0], MessageId::command_ack, "result");
}

TEST(CanNodeStorage, SaveIsAnsweredWhenTheWorkerIsDoneAndConflictsAreBusyMeanwhile) {
  auto r = holding_for_storage();
  ASSERT_TRUE(r);
  const std::uint16_t eta = param_id("x.sliding.eta_mm_s");
  const fw::can::NodeSettings before = r->node->settings();
  EXPECT_TRUE(r->request(command(kRigNode, CommandCode::save_params)).empty()) << "no answer before the write";
  EXPECT_TRUE(r->node->storage_in_flight());
  EXPECT_EQ(r->storage.writes, 0);
  // Conflicting requests while the job is in flight.
  EXPECT_EQ(r->result(command(kRigNode, CommandCode::save_params)), kStorageBusy);
  EXPECT_EQ(r->result(command(kRigNode, CommandCode::load_params)), kStorageBusy);
  EXPECT_EQ(r->result(command(kRigNode, CommandCode::restore_defaults)), kStorageBusy);
  EXPECT_EQ(r->result(command(kRigNode, CommandCode::select_controller, 255, 1)), kStorageBusy);
  EXPECT_EQ(r->result(param_request(kRigNode, ParamOp::set, eta, f32_raw(0.25f))), kStorageBusy);
  EXPECT_EQ(r->result(param_request(kRigNode, ParamOp::stage, eta, f32_raw(0.25f))), kOk) << "staging changes nothing";
  EXPECT_EQ(r->result(param_request(kRigNode, ParamOp::commit, 0)), kStorageBusy);
  EXPECT_EQ(r->result(param_request(kRigNode, ParamOp::get, eta)), kOk) << "reads go on";
  EXPECT_EQ(fw::can::find_param(eta)->get(r->node->settings()), fw::can::find_param(eta)->get(before));
  // One step runs the job on the worker; the next service() answers it.
  std::vector<hal::CanFrame> out;
  for (int k = 0; k < 3 && out.empty(); ++k) {
    r->step();
    out = r->port.drain();
  }
  EXPECT_EQ(storage_ack_result(out, CommandCode::save_params), kOk);
  EXPECT_FALSE(r->node->storage_in_flight());
  EXPECT_EQ(r->storage.writes, 1);
  EXPECT_FALSE(r->node->params_unsaved());
  // The staged set waited and commits now.
  EXPECT_EQ(r->result(param_request(kRigNode, ParamOp::commit, 0)), kOk);
  EXPECT_EQ(r->task().counters().missed_ticks, 0u);
}

TEST(CanNodeStorage, LoadAppliesTheStoredSetWholeWhenTheWorkerIsDone) {
  auto r = holding_for_storage();
  ASSERT_TRUE(r);
  const std::uint16_t eta = param_id("x.sliding.eta_mm_s");
  const fw::can::ParamDef& def = *fw::can::find_param(eta);
  ASSERT_EQ(r->result(param_request(kRigNode, ParamOp::set, eta, f32_raw(0.25f))), kOk);
  EXPECT_EQ(storage_ack_result(r->request_and_wait(command(kRigNode, CommandCode::save_params)), CommandCode::save_params), kOk);
  ASSERT_EQ(r->result(param_request(kRigNode, ParamOp::set, eta, f32_raw(0.1875f))), kOk);
  EXPECT_TRUE(r->node->params_unsaved());
  EXPECT_TRUE(r->request(command(kRigNode, CommandCode::load_params)).empty());
  EXPECT_EQ(def.get(r->node->settings()), 0.1875) << "nothing applied before the read is done";
  EXPECT_EQ(storage_ack_result(r->request_and_wait(param_request(kRigNode, ParamOp::get, eta)), CommandCode::load_params), 255)
      << "the get is answered at once, the load later";
  std::vector<hal::CanFrame> out;
  for (int k = 0; k < 3 && out.empty(); ++k) {
    r->step();
    out = r->port.drain();
  }
  EXPECT_EQ(storage_ack_result(out, CommandCode::load_params), kOk);
  EXPECT_EQ(def.get(r->node->settings()), 0.25);
  EXPECT_EQ(r->task().config().axis[0].sliding.eta_mm_s, 0.25);
  EXPECT_FALSE(r->node->params_unsaved());
}

TEST(CanNodeStorage, AFailedWriteIsAStorageErrorAnsweredLater) {
  auto r = holding_for_storage();
  ASSERT_TRUE(r);
  r->storage.fail_write = true;
  EXPECT_EQ(storage_ack_result(r->request_and_wait(command(kRigNode, CommandCode::save_params)), CommandCode::save_params),
            static_cast<std::uint32_t>(ErrorCode::storage_error));
  EXPECT_TRUE(r->node->storage_fault());
  EXPECT_FALSE(r->node->storage_in_flight());
}

TEST(CanNodeStorage, RestoreDefaultsWhileHoldingGivesThePapersGainsWithoutLosingATick) {
  auto r = holding_for_storage();
  ASSERT_TRUE(r);
  const std::uint16_t kp = param_id("y.pid.kp");
  ASSERT_EQ(r->result(param_request(kRigNode, ParamOp::set, kp, f32_raw(600.0f))), kOk);
  EXPECT_EQ(r->result(command(kRigNode, CommandCode::restore_defaults)), kOk);
  EXPECT_EQ(r->task().config().axis[1].pid.kp, fw::default_firmware_config().axis[1].pid.kp);
  for (int k = 0; k < 5; ++k) r->step();
  EXPECT_EQ(r->task().counters().missed_ticks, 0u);
  EXPECT_EQ(r->rig->charged().charged_calls, 0u);
}

}  // namespace
}  // namespace tnv::test
