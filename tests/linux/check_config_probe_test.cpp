// tnv-fw --check-config stays a check of the file; --probe also opens the
// devices it names and fails, naming each one, when they are not there.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/linux/rig_support.hpp"

namespace tnv {
namespace {

// A board config whose every device is missing.
constexpr const char* kProbeMissingDevices = R"([board]
transport = "spidev"
path = "/dev/nonexistent-spidev9.9"
[can]
interface = "tnvnone0"
[lines]
estop = { chip = "/dev/nonexistent-gpiochip9", offset = 4, active_low = true }
enable_x = { chip = "/dev/nonexistent-gpiochip9", offset = 5 }
)";

struct ProbeRun {
  int exit_code = -1;
  std::string out, err;
};

std::string probe_slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

ProbeRun run_probe_fw(const test::ScratchDir& dir, const std::string& args) {
  const std::string out = dir.file("out.txt"), err = dir.file("err.txt");
  const std::string command = std::string("'") + TNV_FW_EXE + "' " + args + " >'" + out + "' 2>'" + err + "'";
  const int status = std::system(command.c_str());
  ProbeRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = probe_slurp(out);
  r.err = probe_slurp(err);
  return r;
}

std::string write_probe_config(const test::ScratchDir& dir) {
  const std::string path = dir.file("fw.toml");
  std::ofstream(path) << kProbeMissingDevices;
  return path;
}

TEST(CheckConfigProbe, WithoutProbeOnlyTheFileIsChecked) {
  test::ScratchDir dir;
  const std::string config = write_probe_config(dir);
  const ProbeRun r = run_probe_fw(dir, "--config '" + config + "' --check-config");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find(config + ": ok"), std::string::npos) << r.out;
}

TEST(CheckConfigProbe, ProbeNamesEveryMissingDeviceAndFails) {
  test::ScratchDir dir;
  const std::string config = write_probe_config(dir);
  const ProbeRun r = run_probe_fw(dir, "--config '" + config + "' --check-config --probe");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  // One stderr line per device: the config key, the device, the reason.
  const std::string prefix = "tnv-fw: " + config + ": ";
  EXPECT_NE(r.err.find(prefix + "board.path /dev/nonexistent-spidev9.9: cannot open: No such file or directory\n"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(prefix + "lines.estop /dev/nonexistent-gpiochip9:4: no such GPIO chip"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(prefix + "lines.enable_x /dev/nonexistent-gpiochip9:5: no such GPIO chip"), std::string::npos)
      << r.err;
  // No CAN interface of that name; where the kernel has no CAN at all the socket() fails instead.
  EXPECT_NE(r.err.find(prefix + "can.interface tnvnone0: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("probe failed: 4 of 4 devices could not be opened"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find(": ok"), std::string::npos) << r.out;
}

TEST(CheckConfigProbe, CanOptionReplacesTheConfiguredInterface) {
  test::ScratchDir dir;
  const std::string config = write_probe_config(dir);
  const ProbeRun r = run_probe_fw(dir, "--config '" + config + "' --can tnvother0 --check-config --probe");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("can.interface tnvother0: "), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("tnvnone0"), std::string::npos) << r.err;
}

TEST(CheckConfigProbe, ProbeNeedsCheckConfig) {
  test::ScratchDir dir;
  const ProbeRun r = run_probe_fw(dir, "--config '" + write_probe_config(dir) + "' --probe");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
}

}  // namespace
}  // namespace tnv
