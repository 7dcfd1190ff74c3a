// tnv-hil spindle-safety's run (tools/hil/spindle_safety_run.hpp): every
// transition of issue 27 on the emulated machine, judged from the
// emulator's truth. And the judge itself: a firmware whose at-speed window
// is far too wide starts feed moves early, and the judge sees it.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <string>

#include "emulator/scenario_file.hpp"
#include "tools/hil/spindle_safety_run.hpp"

namespace tnv::hil {
namespace {

TEST(SpindleSafety, NoTransitionStartsTheSpindleAndNoFeedMoveBeginsBeforeItIsAtSpeed) {
  const SpindleSafetySummary s = run_spindle_safety(*emu::builtin_scenario("no-cut"));
  ASSERT_EQ(s.transitions.size(), spindle_transition_names().size());
  EXPECT_EQ(s.transitions.size(), 7u);
  EXPECT_EQ(s.self_starts, 0u);
  EXPECT_EQ(s.feed_before_at_speed, 0u);
  EXPECT_GE(s.feed_onsets, 13u) << "every program begins (two per transition, one for the parameter load)";
  const std::map<std::string, std::string> causes = {
      {"feed_hold", "command"},        {"abort", "abort"},           {"fault_clear", "fault"},
      {"estop_release", "estop"},      {"host_timeout", "host_timeout"}, {"node_restart", "restart"},
      {"parameter_load", "command"}};
  for (const SpindleTransitionResult& r : s.transitions) {
    SCOPED_TRACE(r.name);
    EXPECT_EQ(r.stop_cause, causes.at(r.name));
    EXPECT_TRUE(r.stopped);
    EXPECT_FALSE(r.self_start) << r.rise_rpm << " rpm";
    EXPECT_TRUE(r.refused_while_turning);
    EXPECT_TRUE(r.restarted);
    EXPECT_TRUE(r.program_end_stop);
    EXPECT_TRUE(r.ok());
  }
  EXPECT_TRUE(s.all_ok);
}

TEST(SpindleSafety, TheJudgeSeesFeedMovesThatBeginBeforeTheSpindleIsReallyAtSpeed) {
  fw::SpindleParams wide;
  wide.at_speed_fraction = 0.5;  // the firmware calls 50 % of the speed "at speed"
  const SpindleSafetySummary s = run_spindle_safety(*emu::builtin_scenario("no-cut"), wide);
  EXPECT_GT(s.feed_before_at_speed, 0u);
  EXPECT_FALSE(s.all_ok);
  std::printf("a 50 %% at-speed window: %u of %u feed starts before at speed\n", s.feed_before_at_speed,
              s.feed_onsets);
  EXPECT_EQ(s.self_starts, 0u) << "the window has nothing to do with starting";
}

}  // namespace
}  // namespace tnv::hil
