// `tnvctl clear-faults` on a board trip: the first CLEAR_FAULTS resets the
// board's latch and is refused (cause_present), tnvctl sends it once more
// and the fault clears in one command; a cause still asserted stays a
// refusal (exit 1) and the node stays faulted.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "tests/can_host/tnvctl_runner.hpp"

namespace tnv {
namespace {

// The result line of each command (monitor's status lines have no "command").
std::vector<nlohmann::json> command_results(const std::string& out) {
  std::istringstream lines(out);
  std::vector<nlohmann::json> v;
  for (std::string line; std::getline(lines, line);) {
    nlohmann::json j = nlohmann::json::parse(line);
    if (j.contains("command")) v.push_back(std::move(j));
  }
  return v;
}

std::string scripted(const std::filesystem::path& state, const std::string& fault_toml, const std::string& steps) {
  const auto scenario = test::write_file(state / "trip.toml", "name = \"trip\"\n" + fault_toml);
  const auto script = test::write_file(state / "steps.tnvctl", steps);
  std::string args = "--emu --json --emu-scenario ";
  return args.append(scenario.string()).append(" script ").append(script.string());
}

TEST(TnvctlClearFaults, ABoardTripClearsInOneCommand) {
  const auto state = test::state_dir("clear_board_trip");
  // The X decoder latches an illegal transition 0.3 s in (FAULTS bit 0, sticky on the board).
  const std::string args = scripted(state, "[[fault]]\nkind = \"encoder_illegal\"\nstart_s = 0.3\naxis = \"x\"\n",
                                    "enable\nmonitor --duration-s 0.5\nclear-faults\nstatus\n");
  const test::ToolRun r = test::tnvctl(state, args);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const std::vector<nlohmann::json> out = command_results(r.out);
  // Three commands and the script on stdout; monitor's summary went to stderr (stdout stays JSON Lines).
  ASSERT_EQ(out.size(), 4u) << r.out;
  EXPECT_NE(r.err.find("\"command\":\"monitor\""), std::string::npos) << r.err;
  ASSERT_EQ(out[1]["command"], "clear-faults") << r.out;
  EXPECT_EQ(out[1]["retried"], true) << out[1].dump() << ": the first clear only reset the board";
  EXPECT_EQ(out[1]["state"], "disabled") << out[1].dump();
  EXPECT_EQ(out[1]["fault"], "none") << out[1].dump();
  EXPECT_EQ(out[2]["status"]["state"], "disabled") << out[2].dump();
  std::filesystem::remove_all(state);
}

TEST(TnvctlClearFaults, ACauseStillAssertedIsRefusedAndNothingClears) {
  const auto state = test::state_dir("clear_estop_held");
  const std::string args = scripted(state, "[[fault]]\nkind = \"estop\"\nstart_s = 0.3\n",
                                    "enable\nmonitor --duration-s 0.5\nclear-faults\n");
  const test::ToolRun r = test::tnvctl(state, args);
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE((r.out + r.err).find("cause_present"), std::string::npos) << r.out << r.err;
  std::filesystem::remove_all(state);
}

}  // namespace
}  // namespace tnv
