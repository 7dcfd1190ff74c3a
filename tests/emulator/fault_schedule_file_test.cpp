// The [[fault]] schedule in scenario files: every kind and key, and every
// error named by file, line and key with nothing applied.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "emulator/scenario_file.hpp"
#include "emulator/scenario_validation.hpp"

namespace tnv::emu {
namespace {

using ::testing::HasSubstr;

constexpr std::string_view kEveryKind = R"(name = "faults"

[[fault]]
kind = "estop"
start_s = 1.5
duration_s = 0.25

[[fault]]
kind = "servo_alarm"
axis = "y"
start_s = 2

[[fault]]
kind = "limit_switch"
axis = "x"
side = "-"
start_s = 2.5
duration_s = 1

[[fault]]
kind = "encoder_illegal"
axis = "y"
start_s = 3

[[fault]]
kind = "encoder_dead"
axis = "x"
start_s = 3.25

[[fault]]
kind = "dac_stuck"
axis = "y"
code = 4095
start_s = 3.5
duration_s = 0.5

[[fault]]
kind = "missed_tick"
ticks = 3
start_s = 4

[[fault]]
kind = "late_tick"
delay_us = 1500
start_s = 4.5

[[fault]]
kind = "stale_snapshot"
start_s = 5
duration_s = 0.002

[[fault]]
kind = "runaway"
axis = "x"
start_s = 5.5

[[fault]]
kind = "bus_read_error"
start_s = 6
duration_s = 0.001

[[fault]]
kind = "encoder_jump"
axis = "y"
counts = -120
start_s = 6.5

[[fault]]
kind = "snapshot_replayed"
start_s = 7
)";

TEST(FaultScheduleFile, EveryKindAndKeyIsParsed) {
  const ScenarioResult r = parse_scenario_text(kEveryKind, "f.toml");
  ASSERT_TRUE(r.scenario) << r.error;
  const std::vector<FaultSpec>& f = r.scenario->faults;
  ASSERT_EQ(f.size(), kFaultKinds.size());
  for (std::size_t i = 0; i < f.size(); ++i) EXPECT_EQ(f[i].kind, kFaultKinds[i]) << i;
  EXPECT_EQ(f[0].start_s, 1.5);
  EXPECT_EQ(f[0].duration_s, 0.25);
  EXPECT_EQ(f[1].axis, hal::Axis::y);
  EXPECT_EQ(f[1].start_s, 2.0) << "integers are accepted as numbers";
  EXPECT_EQ(f[1].duration_s, 0.0) << "omitted: to the end of the run";
  EXPECT_EQ(f[2].axis, hal::Axis::x);
  EXPECT_FALSE(f[2].positive_side);
  EXPECT_EQ(f[2].duration_s, 1.0);
  EXPECT_EQ(f[5].dac_code, 4095u);
  EXPECT_EQ(f[6].ticks, 3u);
  EXPECT_EQ(f[7].delay_us, 1500.0);
  EXPECT_EQ(f[9].axis, hal::Axis::x);
  EXPECT_EQ(f[10].duration_s, 0.001);
  EXPECT_EQ(f[11].axis, hal::Axis::y);
  EXPECT_EQ(f[11].counts, -120);
  EXPECT_EQ(f[12].start_s, 7.0);
}

TEST(FaultScheduleFile, MissedTickDefaultsToOneTick) {
  const ScenarioResult r = parse_scenario_text("[[fault]]\nkind = \"missed_tick\"\nstart_s = 1\n", "m.toml");
  ASSERT_TRUE(r.scenario) << r.error;
  EXPECT_EQ(r.scenario->faults.at(0).ticks, 1u);
}

struct BadScheduleCase {
  std::string text;
  std::string error;
};

TEST(FaultScheduleFile, ErrorsNameFileLineAndKey) {
  const BadScheduleCase cases[] = {
      {"fault = 3\n", "bad.toml:1:1: fault: expected an array of tables ([[fault]]), got an integer"},
      {"[fault]\nkind = \"estop\"\n", "bad.toml:1:2: fault: expected an array of tables ([[fault]]), got a table"},
      {"[[fault]]\nstart_s = 1\n",
       "bad.toml:1:1: fault[0].kind: required (one of: estop, servo_alarm, limit_switch, encoder_illegal, "
       "encoder_dead, dac_stuck, missed_tick, late_tick, stale_snapshot, runaway, bus_read_error, encoder_jump, snapshot_replayed)"},
      {"[[fault]]\nkind = \"estop\"\nstart_s = 1\n[[fault]]\nkind = \"melt\"\nstart_s = 1\n",
       "bad.toml:5:1: fault[1].kind: unknown kind \"melt\""},
      {"[[fault]]\nkind = 4\n", "bad.toml:2:1: fault[0].kind: expected a string, got an integer"},
      {"[[fault]]\nkind = \"estop\"\n", "bad.toml:1:1: fault[0].start_s: required for kind estop"},
      {"[[fault]]\nkind = \"servo_alarm\"\nstart_s = 1\n", "bad.toml:1:1: fault[0].axis: required for kind servo_alarm"},
      {"[[fault]]\nkind = \"limit_switch\"\naxis = \"x\"\nstart_s = 1\n",
       "bad.toml:1:1: fault[0].side: required for kind limit_switch"},
      {"[[fault]]\nkind = \"dac_stuck\"\naxis = \"x\"\nstart_s = 1\n",
       "bad.toml:1:1: fault[0].code: required for kind dac_stuck"},
      {"[[fault]]\nkind = \"late_tick\"\nstart_s = 1\n", "bad.toml:1:1: fault[0].delay_us: required for kind late_tick"},
      {"[[fault]]\nkind = \"estop\"\nstart_s = 1\ncode = 5\n", "bad.toml:4:1: fault[0].code: not a key of kind estop"},
      {"[[fault]]\nkind = \"missed_tick\"\nstart_s = 1\nduration_s = 5\n",
       "bad.toml:4:1: fault[0].duration_s: not a key of kind missed_tick"},
      {"[[fault]]\nkind = \"estop\"\nstart_s = 1\naxis = \"x\"\n", "bad.toml:4:1: fault[0].axis: not a key of kind estop"},
      {"[[fault]]\nkind = \"runaway\"\naxis = \"w\"\nstart_s = 1\n",
       "bad.toml:3:1: fault[0].axis: must be \"x\", \"y\" or \"z\" (got \"w\")"},
      {"[[fault]]\nkind = \"limit_switch\"\naxis = \"y\"\nside = \"up\"\nstart_s = 1\n",
       "bad.toml:4:1: fault[0].side: must be \"+\" or \"-\" (got \"up\")"},
      {"[[fault]]\nkind = \"estop\"\nstart_s = 1\nwhen = 2\n", "bad.toml:4:1: fault[0].when: unknown key"},
      {"[[fault]]\nkind = \"estop\"\nstart_s = -1\n", "bad.toml:3:1: fault[0].start_s: must be >= 0 and finite (got -1)"},
      {"[[fault]]\nkind = \"estop\"\nstart_s = nan\n",
       "bad.toml:3:1: fault[0].start_s: must be >= 0 and finite (got nan)"},
      {"[[fault]]\nkind = \"estop\"\nstart_s = 1\nduration_s = inf\n",
       "bad.toml:4:1: fault[0].duration_s: must be >= 0 and finite (got inf)"},
      {"[[fault]]\nkind = \"dac_stuck\"\naxis = \"x\"\ncode = 4096\nstart_s = 1\n",
       "bad.toml:4:1: fault[0].code: must be in 0..4095 (got 4096)"},
      {"[dac]\nbits = 10\n[[fault]]\nkind = \"dac_stuck\"\naxis = \"x\"\ncode = 1024\nstart_s = 1\n",
       "bad.toml:6:1: fault[0].code: must be in 0..1023 (got 1024)"},
      {"[[fault]]\nkind = \"dac_stuck\"\naxis = \"x\"\ncode = -1\nstart_s = 1\n",
       "bad.toml:4:1: fault[0].code: must be in 0..4294967295 (got -1)"},
      {"[[fault]]\nkind = \"missed_tick\"\nticks = 0\nstart_s = 1\n",
       "bad.toml:3:1: fault[0].ticks: must be in 1..10000 (got 0)"},
      {"[[fault]]\nkind = \"late_tick\"\ndelay_us = 0\nstart_s = 1\n",
       "bad.toml:3:1: fault[0].delay_us: must be > 0 and <= 1000000 (got 0)"},
      {"[[fault]]\nkind = \"encoder_jump\"\naxis = \"x\"\ncounts = 0\nstart_s = 1\n",
       "bad.toml:4:1: fault[0].counts: must be nonzero (got 0)"},
      {"[[fault]]\nkind = \"encoder_jump\"\naxis = \"x\"\ncounts = 1000001\nstart_s = 1\n",
       "bad.toml:4:1: fault[0].counts: must be in -1000000..1000000 (got 1000001)"},
      {"[[fault]]\nkind = \"encoder_jump\"\naxis = \"x\"\nstart_s = 1\n",
       "fault[0].counts: required for kind encoder_jump"},
      {"[[fault]]\nkind = \"snapshot_replayed\"\naxis = \"x\"\nstart_s = 1\n",
       "bad.toml:3:1: fault[0].axis: not a key of kind snapshot_replayed"},
  };
  for (const BadScheduleCase& c : cases) {
    const ScenarioResult r = parse_scenario_text(c.text, "bad.toml");
    EXPECT_FALSE(r.scenario) << c.text;
    EXPECT_THAT(r.error, HasSubstr(c.error)) << c.text;
    EXPECT_EQ(r.error.find('\n'), std::string::npos) << "one line";
  }
}

TEST(FaultScheduleFile, ValidationCoversScenariosBuiltInCode) {
  Scenario s;
  s.faults.push_back({.kind = FaultKind::late_tick, .start_s = 1.0, .delay_us = -5.0});
  EXPECT_EQ(validate_scenario(s), "fault[0].delay_us: must be > 0 and <= 1000000 (got -5)");
  s.faults[0] = {.kind = FaultKind::missed_tick, .start_s = 1.0, .ticks = 10'001};
  EXPECT_EQ(validate_scenario(s), "fault[0].ticks: must be in 1..10000 (got 10001)");
  s.faults[0] = {.kind = FaultKind::estop, .start_s = 1.0, .duration_s = 0.5};
  EXPECT_EQ(validate_scenario(s), "");
}

}  // namespace
}  // namespace tnv::emu
