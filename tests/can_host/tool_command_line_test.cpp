// The command line every tool shares (tools/cli/cli_frame.hpp): --version,
// an unknown command named with the commands there are, errors prefixed
// with the tool's name, output paths checked before a run; and monitor
// --json as pure JSON Lines on stdout.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "firmware/tick/work_meter.hpp"
#include "tests/can_host/tnvctl_runner.hpp"

namespace tnv {
namespace {

using test::ToolRun;

using test::has;

TEST(ToolCommandLine, VersionPrintsTheToolAndTheProjectVersion) {
  const auto state = test::state_dir("version");
  const ToolRun ctl = test::tnvctl(state, "--version");
  EXPECT_EQ(ctl.exit_code, 0) << ctl.err;
  EXPECT_TRUE(has(ctl.out, "tnvctl 0.")) << ctl.out;
  const ToolRun hil = test::tnv_hil("--version");
  EXPECT_EQ(hil.exit_code, 0) << hil.err;
  EXPECT_TRUE(has(hil.out, "tnv-hil 0.")) << hil.out;
  std::filesystem::remove_all(state);
}

TEST(ToolCommandLine, AnUnknownCommandIsNamedWithTheCommandsThereAre) {
  const auto state = test::state_dir("unknown");
  const ToolRun ctl = test::tnvctl(state, "--emu statsu");
  EXPECT_EQ(ctl.exit_code, 2);
  EXPECT_TRUE(has(ctl.err, "tnvctl: unknown command 'statsu'")) << ctl.err;
  EXPECT_TRUE(has(ctl.err, "status")) << "the commands are listed: " << ctl.err;
  EXPECT_FALSE(has(ctl.err, "A subcommand is required")) << ctl.err;
  const ToolRun none = test::tnvctl(state, "--emu");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_TRUE(has(none.err, "tnvctl: which command?")) << none.err;
  const ToolRun hil = test::tnv_hil("circel");
  EXPECT_EQ(hil.exit_code, 2);
  EXPECT_TRUE(has(hil.err, "tnv-hil: unknown command 'circel'")) << hil.err;
  const ToolRun option = test::tnv_hil("circle --no-such-option");
  EXPECT_EQ(option.exit_code, 2);
  EXPECT_TRUE(has(option.err, "tnv-hil: ")) << "the tool names itself: " << option.err;
  std::filesystem::remove_all(state);
}

// tnv-hil builds the option trees only up to the named command's family
// (tools/tnv-hil/main.cpp): every command --help lists must still parse,
// and a second command word is still refused.
TEST(ToolCommandLine, EveryTnvHilCommandParsesWhenNamedFirst) {
  const ToolRun all = test::tnv_hil("--help");
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const std::size_t from = all.out.find("Subcommands:");
  ASSERT_NE(from, std::string::npos) << all.out;
  std::istringstream lines(all.out.substr(from));
  std::string line;
  std::getline(lines, line);
  int commands = 0;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string name;
    if (!(words >> name)) continue;
    const ToolRun one = test::tnv_hil(name + " --help");
    EXPECT_EQ(one.exit_code, 0) << name << ": " << one.err;
    EXPECT_TRUE(has(one.out, name)) << name << ": " << one.out;
    ++commands;
  }
  EXPECT_GE(commands, 15) << all.out;
  const ToolRun two = test::tnv_hil("circle table3");
  EXPECT_EQ(two.exit_code, 2) << two.err;
  EXPECT_EQ(two.out, "") << "nothing may run";
}

// An [io] scenario in a tnv-hil without the work meter (the package's) is
// run, with a warning on stderr and "io_work_unmetered" in its JSON; a
// metered build, or a scenario without [io], shows neither.
TEST(ToolCommandLine, TnvHilSaysWhenAnIoRunIsUnmetered) {
  const ToolRun bench = test::tnv_hil("circle --scenario bench-no-cut --controller rdvsc --json");
  ASSERT_EQ(bench.exit_code, 0) << bench.err;
  const nlohmann::json j = nlohmann::json::parse(bench.out, nullptr, false);
  ASSERT_FALSE(j.is_discarded()) << bench.out;
  const bool unmetered = !fw::work_meter_enabled();
  EXPECT_EQ(j.contains("io_work_unmetered"), unmetered) << bench.out;
  EXPECT_EQ(has(bench.err, "warning: scenario 'bench-no-cut' has [io] on"), unmetered) << bench.err;
  const ToolRun plain = test::tnv_hil("circle --scenario no-cut --controller rdvsc --json");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_FALSE(has(plain.out, "io_work_unmetered")) << plain.out;
  EXPECT_FALSE(has(plain.err, "warning")) << plain.err;
}

TEST(ToolCommandLine, AnOutputThatCannotBeWrittenIsRefusedBeforeTheRun) {
  const auto state = test::state_dir("outputs");
  const std::string fifo = (state / "fifo").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& args : {"circle --csv " + fifo, "circle --plot " + (state / "no" / "x.svg").string(),
                                  "circle --plot " + state.string(), "table3 --plot-dir " + fifo + "/d"}) {
    const ToolRun r = test::tnv_hil(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_EQ(r.out, "") << args << ": nothing may run";
    EXPECT_TRUE(has(r.err, "tnv-hil: --")) << "the option is named: " << r.err;
  }
  const ToolRun ctl = test::tnvctl(state, "--emu capture --circle --csv " + fifo);
  EXPECT_EQ(ctl.exit_code, 2) << ctl.err;
  EXPECT_TRUE(has(ctl.err, "not a regular file")) << ctl.err;
  std::filesystem::remove_all(state);
}

TEST(ToolCommandLine, MonitorJsonIsJsonLinesOnStdoutWithTheSummaryOnStderr) {
  const auto state = test::state_dir("monitor_json");
  const ToolRun r = test::tnvctl(state, "--emu --json monitor --duration-s 0.3 --rate-hz 20");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream out(r.out);
  int samples = 0;
  for (std::string line; std::getline(out, line);) {
    const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << "not one JSON object per line: " << line;
    EXPECT_TRUE(j.contains("t_s")) << line;
    EXPECT_FALSE(j.contains("exit_code")) << "the summary is on stdout: " << line;
    ++samples;
  }
  EXPECT_GE(samples, 4);
  const std::string last = r.err.substr(r.err.rfind('{'));
  const nlohmann::json summary = nlohmann::json::parse(last);
  EXPECT_EQ(summary["ok"], true);
  EXPECT_EQ(summary["command"], "monitor");
  EXPECT_EQ(summary["lines"].get<int>(), samples);
  std::filesystem::remove_all(state);
}

// The monitor asks for the program's state (COMMAND program_status): a node just started knows no tool.
TEST(ToolCommandLine, MonitorShowsTheToolInTheSpindleAsTheNodeKnowsIt) {
  const auto state = test::state_dir("monitor_tool");
  const ToolRun r = test::tnvctl(state, "--emu monitor --duration-s 0.3 --rate-hz 20");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "in spindle: unknown")) << r.out;
  std::filesystem::remove_all(state);
}

TEST(ToolCommandLine, MonitorCsvHasOneHeaderAndFullRowsOnStdoutAndRefusesJsonToo) {
  const auto state = test::state_dir("monitor_csv");
  const ToolRun r = test::tnvctl(state, "--emu monitor --csv --duration-s 0.3 --rate-hz 20");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream out(r.out);
  std::string header;
  ASSERT_TRUE(std::getline(out, header));
  EXPECT_EQ(header.rfind("t_s,frames,bus_load,state,fault,pos_x_mm,pos_y_mm,", 0), 0u) << header;
  const auto columns = std::count(header.begin(), header.end(), ',');
  int rows = 0;
  std::string last;
  for (std::string line; std::getline(out, line); ++rows) {
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), columns) << line;
    last = line;
  }
  EXPECT_GE(rows, 4);
  EXPECT_NE(last.find(",disabled,none,"), std::string::npos) << "state and fault by name, once a heartbeat came: "
                                                              << last;
  EXPECT_TRUE(has(r.err, "frames from node 1")) << "the summary goes to stderr: " << r.err;
  const ToolRun both = test::tnvctl(state, "--emu --json monitor --csv --duration-s 0.1");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_TRUE(has(both.err, "--csv and --json")) << both.err;
  std::filesystem::remove_all(state);
}

}  // namespace
}  // namespace tnv
