// tnvctl --trace, decode and replay as a user runs them: record a session,
// read it by name, send it again to a fresh node and see the same effect.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/can_host/tnvctl_runner.hpp"

namespace tnv {
namespace {

using test::ToolRun;

using test::has;

TEST(TnvctlTrace, ARecordedSessionDecodesByNameAndReplaysOntoAFreshNode) {
  const auto state = test::state_dir("trace");
  const auto trace = state / "session.log";
  ToolRun r = test::tnvctl(state, "--emu --trace " + trace.string() + " params set x.sliding.gamma=0.3125");
  ASSERT_EQ(r.exit_code, 0) << r.err;

  r = test::tnvctl(state, "decode " + trace.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "PARAM_REQUEST node 1")) << r.out;
  EXPECT_TRUE(has(r.out, "param=0x0116 (x.sliding.gamma)  value=0.3125")) << r.out;
  EXPECT_TRUE(has(r.out, "PARAM_REPLY node 1")) << r.out;
  EXPECT_TRUE(has(r.out, "code=take_ownership")) << r.out;
  r = test::tnvctl(state, "--json decode - < " + trace.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json first = nlohmann::json::parse(r.out.substr(0, r.out.find('\n')));
  EXPECT_EQ(first["iface"], "emu");
  EXPECT_TRUE(first.contains("text"));

  // A fresh node (nothing was saved) takes the recorded set again.
  r = test::tnvctl(state, "--emu --json params get x.sliding.gamma");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(nlohmann::json::parse(r.out)["params"][0]["value"], 0.3125);
  const auto replay_script = test::write_file(state / "replay.tnvctl", "replay " + trace.string() +
                                                                           "\nparams get x.sliding.gamma\n");
  r = test::tnvctl(state, "--emu script " + replay_script.string());
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_TRUE(has(r.out, "replayed ")) << r.out;
  EXPECT_TRUE(has(r.out, "<- PARAM_REPLY node 1")) << r.out;
  EXPECT_TRUE(has(r.out, "x.sliding.gamma = 0.3125")) << r.out;

  // A line that is not a frame: exit 2, naming file and line, nothing sent.
  const auto bad = test::write_file(state / "bad.log", "(1.0) emu 241#00\nnot a frame\n");
  r = test::tnvctl(state, "--emu replay " + bad.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "bad.log:2: ")) << r.err;
  EXPECT_EQ(test::tnvctl(state, "decode " + state.string()).exit_code, 2) << "a directory is not a trace";
  EXPECT_EQ(test::tnvctl(state, "--emu --trace /nonexistent-dir/t.log status").exit_code, 2)
      << "the trace path is checked before the run";
  std::filesystem::remove_all(state);
}

}  // namespace
}  // namespace tnv
