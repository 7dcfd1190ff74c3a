// BORE_GAUGE on the node: its answers are the direct planner's, part after
// part; query and restart; what was learned is unsaved until saved, and a
// node restarted from the saved image between two parts continues with
// identical infeeds.
#include <gtest/gtest.h>

#include <array>
#include <memory>

#include "firmware/can/node_fields.hpp"
#include "firmware/can/param_image.hpp"
#include "tests/firmware/can/bore_frames.hpp"

namespace tnv::test {
namespace {

using fw::can::BoreOp;
using fw::can::ErrorCode;
using fw::can::MessageId;

struct BoreReply {
  ErrorCode result = ErrorCode::ok;
  std::uint32_t tag = 0, detail = 0, flags = 0;
  std::array<double, 2> infeed{};
};

BoreReply bore_reply(NodeBench& b, const hal::CanFrame& request) {
  const hal::CanFrame f = b.reply(request);
  EXPECT_TRUE(is(f, MessageId::bore_infeed)) << "no single BORE_INFEED";
  BoreReply r;
  r.result = static_cast<ErrorCode>(raw_of(f, MessageId::bore_infeed, "result"));
  r.tag = raw_of(f, MessageId::bore_infeed, "tag");
  r.detail = raw_of(f, MessageId::bore_infeed, "detail");
  r.flags = raw_of(f, MessageId::bore_infeed, "flags");
  r.infeed = {value_of(f, MessageId::bore_infeed, "infeed_top"), value_of(f, MessageId::bore_infeed, "infeed_bottom")};
  return r;
}

// The frame a host sends for part `part` cut with `infeed`: S4's process, gauged.
hal::CanFrame gauged_part(int part, const std::array<double, 2>& infeed) {
  return bore_gauge(kNode, BoreOp::record, static_cast<std::uint32_t>(part),
                    s4_bore_error_mm(s4_deflection_mm(part, infeed[0], 40.0, 0.01)),
                    s4_bore_error_mm(s4_deflection_mm(part, infeed[1], 310.0, 0.01)));
}

TEST(CanNodeBoring, TheNodeAnswersWhatTheDirectPlannerPlansPartAfterPart) {
  NodeBench b(boring_settings());
  const fw::can::NodeSettings& s = b.node->settings();
  fw::BoringInfeedPlanner direct(fw::planner_params(s.bore));
  const double step = fw::can::fields::kBoreInfeedTop.scale;
  BoreReply r = bore_reply(b, bore_gauge(kNode, BoreOp::query));
  ASSERT_EQ(r.result, ErrorCode::ok);
  int resets = 0;
  for (int part = 1; part <= 30; ++part) {
    std::array<double, 2> planned{};
    for (int i = 0; i < 2; ++i)
      planned[static_cast<std::size_t>(i)] = fw::on_infeed_grid(direct.infeed(i == 0 ? 40.0 : 310.0).infeed_mm_rev, step);
    ASSERT_EQ(r.infeed, planned) << "part " << part << ": the infeeds told for it";
    const hal::CanFrame gauge = gauged_part(part, r.infeed);
    const std::array<double, 2> reading = bore_readings(gauge);
    const fw::BoreMeasurement m[2] = {{40.0, planned[0], reading[0]}, {310.0, planned[1], reading[1]}};
    const fw::BoringPartReport expected = direct.record_part(m);
    ASSERT_TRUE(expected.check.ok);
    r = bore_reply(b, gauge);
    ASSERT_EQ(r.result, ErrorCode::ok) << "part " << part;
    EXPECT_EQ(r.tag, kTestTag);
    EXPECT_EQ((r.flags & fw::can::kBoreStarted) != 0, true);
    EXPECT_EQ((r.flags & fw::can::kBoreStartup) != 0, expected.startup) << "part " << part;
    EXPECT_EQ((r.flags & fw::can::kBoreReset) != 0, expected.reset) << "part " << part;
    const int out = ((r.flags & fw::can::kBoreTopOut) != 0 ? 1 : 0) + ((r.flags & fw::can::kBoreBottomOut) != 0 ? 1 : 0);
    EXPECT_EQ(out, expected.out_of_band) << "part " << part;
    resets += expected.reset ? 1 : 0;
    EXPECT_TRUE(s.bore_state.planner == direct.state()) << "part " << part;
    EXPECT_EQ(b.param("bore.parts"), part);
  }
  EXPECT_GE(resets, 1) << "the large change at part 11 resets P";
  EXPECT_EQ(b.param("bore.resets"), resets);
  EXPECT_EQ(b.param("bore.alpha_hat"), direct.estimated_alpha());
  EXPECT_EQ(b.param("bore.beta_hat"), direct.estimated_beta());
  EXPECT_EQ(b.param("bore.c_hat_mm"), direct.estimated_c_mm());
}

TEST(CanNodeBoring, QueryChangesNothingAndAnyHostMayAsk) {
  NodeBench b(boring_settings());
  BoreReply r = bore_reply(b, bore_gauge(kNode, BoreOp::query));
  EXPECT_EQ(r.flags, 0u) << "not started";
  EXPECT_EQ(r.infeed[0], 0.5) << "S0";
  r = bore_reply(b, gauged_part(1, r.infeed));
  ASSERT_EQ(r.result, ErrorCode::ok);
  EXPECT_NE(r.flags & fw::can::kBoreStartup, 0u);
  const fw::BoringStationState learned = b.node->settings().bore_state;
  const BoreReply q = bore_reply(b, with_tag(bore_gauge(kNode, BoreOp::query), 0x25));
  EXPECT_EQ(q.result, ErrorCode::ok);
  EXPECT_EQ(q.tag, 0x25u);
  EXPECT_EQ(q.infeed, r.infeed) << "the infeeds of the part to cut now";
  EXPECT_EQ(q.flags, static_cast<std::uint32_t>(fw::can::kBoreStarted)) << "only the state bit";
  EXPECT_TRUE(b.node->settings().bore_state == learned);
}

TEST(CanNodeBoring, RestartStartsTheLearningAgainAtS0) {
  NodeBench b(boring_settings());
  BoreReply r = bore_reply(b, bore_gauge(kNode, BoreOp::query));
  for (int part = 1; part <= 3; ++part) r = bore_reply(b, gauged_part(part, r.infeed));
  ASSERT_EQ(b.param("bore.parts"), 3.0);
  r = bore_reply(b, bore_gauge(kNode, BoreOp::restart));
  EXPECT_EQ(r.result, ErrorCode::ok);
  EXPECT_EQ(r.flags, 0u);
  EXPECT_EQ(r.infeed[0], 0.5);
  EXPECT_EQ(r.infeed[1], 0.5);
  EXPECT_EQ(b.param("bore.parts"), 0.0);
  EXPECT_TRUE(b.node->settings().bore_state == fw::BoringStationState{});
  EXPECT_EQ(bore_reply(b, gauged_part(1, r.infeed)).result, ErrorCode::ok) << "part 1 again";
}

TEST(CanNodeBoring, WhatWasLearnedIsUnsavedUntilSavedAndSurvivesRestoreDefaults) {
  NodeBench b(boring_settings());
  EXPECT_FALSE(b.node->params_unsaved());
  BoreReply r = bore_reply(b, bore_gauge(kNode, BoreOp::query));
  r = bore_reply(b, gauged_part(1, r.infeed));
  EXPECT_TRUE(b.node->params_unsaved()) << "a recorded part is not saved yet";
  EXPECT_NE(b.node->heartbeat_errors() & fw::can::kHbParamsUnsaved, 0u);
  ASSERT_EQ(raw_of(b.reply(command(kNode, fw::can::CommandCode::save_params)), MessageId::command_ack, "result"), 0u);
  EXPECT_FALSE(b.node->params_unsaved());
  bore_reply(b, bore_gauge(kNode, BoreOp::query));
  EXPECT_FALSE(b.node->params_unsaved()) << "a query learns nothing";
  const fw::BoringStationState learned = b.node->settings().bore_state;
  ASSERT_EQ(raw_of(b.reply(command(kNode, fw::can::CommandCode::restore_defaults)), MessageId::command_ack, "result"), 0u);
  EXPECT_TRUE(b.node->settings().bore_state == learned) << "restore_defaults keeps what was learned";
  EXPECT_FALSE(b.node->settings().bore.enabled) << "... and the settings go back to theirs (off)";
}

TEST(CanNodeBoring, ANodeRestartedFromItsSavedImageBetweenTwoPartsContinuesWithIdenticalInfeeds) {
  NodeBench running(boring_settings());
  BoreReply r = bore_reply(running, bore_gauge(kNode, BoreOp::query));
  for (int part = 1; part <= 12; ++part) r = bore_reply(running, gauged_part(part, r.infeed));
  ASSERT_EQ(raw_of(running.reply(command(kNode, fw::can::CommandCode::save_params)), MessageId::command_ack, "result"), 0u);

  // Power cycle: a new node loads the image at start-up, from the defaults (planner state fresh).
  fw::can::NodeSettings loaded = boring_settings();
  ASSERT_EQ(fw::can::load_settings(running.storage, loaded), ErrorCode::ok);
  NodeBench restarted(loaded);
  EXPECT_TRUE(restarted.node->settings().bore_state == running.node->settings().bore_state);
  EXPECT_FALSE(restarted.node->params_unsaved());
  BoreReply q = bore_reply(restarted, bore_gauge(kNode, BoreOp::query));
  EXPECT_EQ(q.infeed, r.infeed) << "part 13's infeeds, as told before the restart";

  BoreReply a = r;
  BoreReply c = q;
  int resets = 0;
  for (int part = 13; part <= 30; ++part) {
    a = bore_reply(running, gauged_part(part, a.infeed));
    c = bore_reply(restarted, gauged_part(part, c.infeed));
    ASSERT_EQ(a.result, ErrorCode::ok);
    ASSERT_EQ(c.result, ErrorCode::ok);
    EXPECT_EQ(c.infeed, a.infeed) << "part " << part + 1 << "'s infeeds";
    EXPECT_EQ(c.flags, a.flags) << "part " << part;
    resets += (a.flags & fw::can::kBoreReset) != 0 ? 1 : 0;
  }
  EXPECT_TRUE(restarted.node->settings().bore_state == running.node->settings().bore_state);
  EXPECT_GE(resets + static_cast<int>(running.param("bore.resets")), 1);
}

TEST(CanNodeBoring, LoadParamsPutsBackTheSavedLearningWhole) {
  NodeBench b(boring_settings());
  BoreReply r = bore_reply(b, bore_gauge(kNode, BoreOp::query));
  for (int part = 1; part <= 4; ++part) r = bore_reply(b, gauged_part(part, r.infeed));
  ASSERT_EQ(raw_of(b.reply(command(kNode, fw::can::CommandCode::save_params)), MessageId::command_ack, "result"), 0u);
  const fw::BoringStationState saved = b.node->settings().bore_state;
  for (int part = 5; part <= 7; ++part) r = bore_reply(b, gauged_part(part, r.infeed));
  ASSERT_FALSE(b.node->settings().bore_state == saved);
  ASSERT_EQ(raw_of(b.reply(command(kNode, fw::can::CommandCode::load_params)), MessageId::command_ack, "result"), 0u);
  EXPECT_TRUE(b.node->settings().bore_state == saved);
  EXPECT_EQ(b.param("bore.parts"), 4.0);
}

TEST(CanNodeBoring, ASettingChangeKeepsTheLearningAndAppliesFromTheNextPart) {
  NodeBench b(boring_settings());
  BoreReply r = bore_reply(b, bore_gauge(kNode, BoreOp::query));
  for (int part = 1; part <= 3; ++part) r = bore_reply(b, gauged_part(part, r.infeed));
  const fw::BoringStationState learned = b.node->settings().bore_state;
  const std::uint16_t d0 = id_of("bore.d0_mm");
  ASSERT_EQ(raw_of(b.reply(param_request(kNode, fw::can::ParamOp::set, d0, f32_raw(0.1f))), MessageId::param_reply,
                   "result"),
            0u);
  EXPECT_TRUE(b.node->settings().bore_state == learned);
  EXPECT_EQ(bore_reply(b, bore_gauge(kNode, BoreOp::query)).infeed, r.infeed) << "the part being cut keeps its infeeds";
  // Part 4 is recorded with its told infeeds and the new d0: what a planner with the new settings and the same learning does.
  fw::BoringInfeedPlanner direct(fw::planner_params(b.node->settings().bore));
  ASSERT_EQ(direct.params().target_deflection_mm, static_cast<double>(0.1f));
  ASSERT_TRUE(direct.restore(learned.planner).ok);
  const hal::CanFrame gauge = gauged_part(4, r.infeed);
  const std::array<double, 2> reading = bore_readings(gauge);
  const fw::BoreMeasurement m[2] = {{40.0, r.infeed[0], reading[0]}, {310.0, r.infeed[1], reading[1]}};
  ASSERT_TRUE(direct.record_part(m).check.ok);
  const BoreReply next = bore_reply(b, gauge);
  ASSERT_EQ(next.result, ErrorCode::ok);
  const double step = fw::can::fields::kBoreInfeedTop.scale;
  EXPECT_EQ(next.infeed[0], fw::on_infeed_grid(direct.infeed(40.0).infeed_mm_rev, step));
  EXPECT_EQ(next.infeed[1], fw::on_infeed_grid(direct.infeed(310.0).infeed_mm_rev, step));
  EXPECT_EQ(b.param("bore.parts"), 4.0) << "the learning went on";
}

}  // namespace
}  // namespace tnv::test
