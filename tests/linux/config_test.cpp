// tnv-fw's config file: every key read, every refusal one line naming the
// file, the line and the key.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <string_view>

#include "tools/tnv-fw/fw_config.hpp"

namespace tnv {
namespace {

// a + b by append: GCC 12 at -O1 (the test code of a Release build) warns
// falsely, -Warray-bounds, on std::string(a) + "literal" (the plain build
// stopped here; the unity batch happened not to inline it that way).
std::string joined(std::string a, std::string_view b) {
  a.append(b);
  return a;
}

constexpr const char* kMinimal = "[board]\ntransport = \"socket\"\npath = \"/run/tnv/board.sock\"\n";

std::string error_of(const std::string& text) {
  const fwd::ConfigResult r = fwd::parse_daemon_config(text, "fw.toml");
  return r.config ? "(accepted)" : r.error;
}

TEST(DaemonConfig, AMinimalFileTakesTheDefaults) {
  const fwd::ConfigResult r = fwd::parse_daemon_config(kMinimal, "fw.toml");
  ASSERT_TRUE(r.config) << r.error;
  EXPECT_EQ(r.config->board.transport, "socket");
  EXPECT_EQ(r.config->can.interface_name, "can0");
  EXPECT_EQ(r.config->can.node_id, 1);
  EXPECT_EQ(r.config->rt.priority, 80);
  EXPECT_TRUE(r.config->rt.require);
  EXPECT_EQ(r.config->tick.period_us, 1000u);
  EXPECT_FALSE(r.config->lines.any());
  EXPECT_FALSE(r.config->safety.allow_commissioning) << "commissioning is off unless the file allows it";
}

TEST(DaemonConfig, EveryKeyIsRead) {
  const std::string text = joined(kMinimal, R"(connect_timeout_ms = 100
reply_timeout_ms = 5
[can]
interface = "vcan0"
node_id = 7
[lines]
tick = { chip = "gpiochip1", offset = 3 }
estop = { name = "TNV_ESTOP", active_low = true }
enable_y = { chip = "gpiochip0", offset = 12 }
[rt]
priority = 90
cpu = 1
require = false
[tick]
period_us = 10000
[params]
file = "/tmp/p.bin"
[safety]
allow_commissioning = true
)");
  const fwd::ConfigResult r = fwd::parse_daemon_config(text, "fw.toml");
  ASSERT_TRUE(r.config) << r.error;
  const fwd::DaemonConfig& c = *r.config;
  EXPECT_EQ(c.board.connect_timeout_ms, 100);
  EXPECT_EQ(c.board.reply_timeout_ms, 5);
  EXPECT_EQ(c.can.interface_name, "vcan0");
  EXPECT_EQ(c.can.node_id, 7);
  EXPECT_EQ(c.lines.tick.chip, "gpiochip1");
  EXPECT_EQ(c.lines.tick.offset, 3);
  const drivers::LineSpec& estop = c.lines.inputs[static_cast<std::size_t>(drivers::InputLine::estop)];
  EXPECT_EQ(estop.name, "TNV_ESTOP");
  EXPECT_TRUE(estop.active_low);
  EXPECT_EQ(c.lines.outputs[static_cast<std::size_t>(drivers::OutputLine::enable_y)].offset, 12);
  EXPECT_FALSE(c.lines.outputs[static_cast<std::size_t>(drivers::OutputLine::enable_x)].configured());
  EXPECT_EQ(c.rt.priority, 90);
  EXPECT_EQ(c.rt.cpu, 1);
  EXPECT_FALSE(c.rt.require);
  EXPECT_EQ(c.tick.period_us, 10000u);
  EXPECT_EQ(c.params.file, "/tmp/p.bin");
  EXPECT_TRUE(c.safety.allow_commissioning);
}

TEST(DaemonConfig, RefusalsAreOneLineWithFileLineAndKey) {
  const std::string board = kMinimal;  // lines 1-3
  struct Case {
    std::string text;
    std::string error;
  };
  const Case cases[] = {
      {"", "fw.toml:1: board.transport: missing (\"socket\" or \"spidev\")"},
      {"[board]\ntransport = \"uart\"\n", "fw.toml:2: board.transport: must be \"socket\" or \"spidev\" (got \"uart\")"},
      {"\n[board]\ntransport = \"spidev\"\n", "fw.toml:2: board.path: missing (e.g. /dev/spidev0.0)"},
      {board + "spi_speed_hz = 1000000\n", "fw.toml:4: board.spi_speed_hz: only for transport = \"spidev\""},
      {board + "reply_timeout_ms = 0\n", "fw.toml:4: board.reply_timeout_ms: must be 1..10000 (got 0)"},
      {board + "colour = 3\n",
       "fw.toml:4: board.colour: unknown key (known: transport path spi_speed_hz connect_timeout_ms reply_timeout_ms)"},
      {board + "[can]\nnode_id = 32\n", "fw.toml:5: can.node_id: must be 1..31 (got 32)"},
      {board + "[can]\nnode_id = \"1\"\n", "fw.toml:5: can.node_id: must be an integer 1..31, not a string"},
      {board + "[can]\ninterface = \"a-very-long-ifname0\"\n",
       "fw.toml:5: can.interface: a network interface name has at most 15 characters"},
      {board + "[rt]\npriority = 150\n", "fw.toml:5: rt.priority: must be 0..99 (got 150)"},
      {board + "[rt]\nrequire = 1\n", "fw.toml:5: rt.require: must be true or false, not an integer"},
      {board + "[safety]\nallow_commissioning = \"yes\"\n",
       "fw.toml:5: safety.allow_commissioning: must be true or false, not a string"},
      {board + "[safety]\nallow = true\n", "fw.toml:5: safety.allow: unknown key (known: allow_commissioning)"},
      {board + "[rt]\ncpu = -2\n", "fw.toml:5: rt.cpu: must be -1..1023 (got -2)"},
      {board + "[tick]\nperiod_us = 50\n", "fw.toml:5: tick.period_us: must be 100..100000 (got 50)"},
      {board + "[lines]\ntick = 4\n",
       "fw.toml:5: lines.tick: must be a table {chip = \"gpiochip0\", offset = N} or {name = \"LINE\"}, not an integer"},
      {board + "[lines]\nestop = { chip = \"gpiochip0\" }\n", "fw.toml:5: lines.estop: needs both chip and offset"},
      {board + "[lines]\nestop = { name = \"E\", offset = 2, chip = \"c\" }\n",
       "fw.toml:5: lines.estop: give either name or chip + offset, not both"},
      {board + "[lines]\nenable_z = { name = \"E\" }\n",
       "fw.toml:5: lines.enable_z: unknown key (known: tick estop alarm_x alarm_y limit_x_pos limit_x_neg limit_y_pos "
       "limit_y_neg enable_x enable_y)"},
      {board + "[lines]\nalarm_x = { name = \"A\", pull = \"up\" }\n",
       "fw.toml:5: lines.alarm_x.pull: unknown key (known: chip offset name active_low)"},
      {board + "[params]\nfile = \"\"\n", "fw.toml:5: params.file: must not be empty"},
      {board + "[watchdog]\n", "fw.toml:4: watchdog: unknown key (known: board can lines rt tick params safety)"},
      {board + "[rt\n", "fw.toml:4: TOML syntax: "},
  };
  for (const Case& c : cases) {
    const std::string got = error_of(c.text);
    if (c.error.ends_with(": ")) {
      EXPECT_TRUE(got.starts_with(c.error)) << got;
    } else {
      EXPECT_EQ(got, c.error) << "for:\n" << c.text;
    }
    EXPECT_EQ(got.find('\n'), std::string::npos) << "one line: " << got;
  }
}

TEST(DaemonConfig, APeriodOtherThan1msParsesButCannotRunTheFirmware) {
  const fwd::ConfigResult r = fwd::parse_daemon_config(joined(kMinimal, "[tick]\nperiod_us = 10000\n"), "fw.toml");
  ASSERT_TRUE(r.config) << "--latency-test measures any period: " << r.error;
  EXPECT_EQ(fwd::daemon_run_error(*r.config),
            "tick.period_us: must be 1000 to run the firmware: its models, trajectories and late-tick check are built "
            "for a 1 ms tick (got 10000; other periods are for --latency-test only)");
  fwd::DaemonConfig ok = *r.config;
  ok.tick.period_us = 1000;
  EXPECT_EQ(fwd::daemon_run_error(ok), "");
}

TEST(DaemonConfig, AMissingFileIsNamed) {
  const fwd::ConfigResult r = fwd::load_daemon_config("/nonexistent/tnv-fw.toml");
  EXPECT_EQ(r.error, "/nonexistent/tnv-fw.toml: cannot open: No such file or directory");
}

TEST(DaemonConfig, ADeviceOrADirectoryAsTheConfigIsRefusedAtOnce) {
  // /dev/zero took 4.5 GB in 8 s before the type and size checks.
  EXPECT_EQ(fwd::load_daemon_config("/dev/zero").error, "/dev/zero: refused: a character device, not a regular file");
  EXPECT_EQ(fwd::load_daemon_config("/").error, "/: refused: a directory, not a regular file");
}

TEST(DaemonConfig, ThePackagedDefaultConfigIsValid) {
  const fwd::ConfigResult r = fwd::load_daemon_config(joined(TNV_SOURCE_DIR, "/packaging/tnv-fw.toml"));
  ASSERT_TRUE(r.config) << r.error;
  EXPECT_EQ(r.config->board.transport, "spidev");
  EXPECT_TRUE(r.config->rt.require) << "the board default refuses to run without SCHED_FIFO";
  EXPECT_FALSE(r.config->safety.allow_commissioning) << "the shipped board refuses commissioning";
}

}  // namespace
}  // namespace tnv
