// The layering is a rule, not a hope (design notes "Layers"), checked as an
// allow-list: per layer, the include roots and standard headers it may use;
// anything else fails with file, line and the include.
//  - firmware/: firmware/, hal/, Eigen and the standard headers that
//    cannot block, sleep, log, allocate by design or do I/O (no <mutex>,
//    <thread>, <chrono>, <iostream>, <vector>, <string>, no POSIX);
//  - hal/: interfaces only (no .cpp), hal/ and a handful of vocabulary
//    headers;
//  - emulator/: emulator/, hal/ (the register map and axis names), the C++
//    standard library and toml++; never firmware/ or drivers/, no POSIX
//    except the three headers of emulator/text_file.cpp (a FIFO or device
//    must be refused by fstat on an fd opened non-blocking, which
//    <filesystem> cannot do without a race);
//  - drivers/: never firmware/;
//  - tools/tune/ (the tuning library): tools/tune/, firmware/, hal/, Eigen
//    and the standard library without threads or files (no emulator, no
//    HIL rig, no JSON, no CLI; its link closure: layering.tune_links);
//  - tools/score/ (tnv_score, what tnv-hil and tnvctl judge a run by):
//    tools/score/, tools/gcode/, firmware/, hal/, Eigen, nlohmann/json and
//    the standard library without threads or files (its link closure:
//    layering.score_links);
//  - tools/gcode/ (tnv_gcode_lib): never the emulator nor the HIL rig (it
//    reads files with drivers/storage/regular_file.hpp; layering.gcode_links);
//  - tools/can/ (tnv_can_host): never the emulated node (tools/can_emu/,
//    drivers/emulated/), the HIL rig (tools/hil/) or the emulator; what it
//    shares with tnv-hil is tools/score/ (its link closure:
//    layering.can_host_links).
//  - tools/tnvctl/: the emulator and the rig only through tools/can_emu/.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct Include {
  std::string file;
  int line;
  std::string target;
  bool angle;  // <...> rather than "..."
};

// The target of an #include line, or "" (std::regex trips a GCC 12 false
// warning under the sanitizers, and this needs no more than a scan).
std::string include_target(const std::string& line) {
  std::size_t i = line.find_first_not_of(" \t");
  if (i == std::string::npos || line[i] != '#') return {};
  i = line.find_first_not_of(" \t", i + 1);
  if (i == std::string::npos || line.compare(i, 7, "include") != 0) return {};
  i = line.find_first_not_of(" \t", i + 7);
  if (i == std::string::npos || (line[i] != '<' && line[i] != '"')) return {};
  const std::size_t end = line.find(line[i] == '<' ? '>' : '"', i + 1);
  return end == std::string::npos ? std::string{} : line.substr(i + 1, end - i - 1);
}

std::vector<Include> includes_under(const std::string& dir) {
  std::vector<Include> out;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(TNV_SOURCE_DIR) / dir)) {
    const auto ext = entry.path().extension();
    if (ext != ".hpp" && ext != ".cpp") continue;
    std::ifstream in(entry.path());
    std::string text;
    int n = 0;
    while (std::getline(in, text)) {
      ++n;
      if (std::string target = include_target(text); !target.empty()) {
        const std::size_t open = text.find_first_of("<\"");
        const bool angle = open != std::string::npos && text[open] == '<';
        out.push_back({entry.path().lexically_relative(TNV_SOURCE_DIR).string(), n, std::move(target), angle});
      }
    }
  }
  return out;
}

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

bool in(const std::set<std::string>& set, const std::string& s) { return set.count(s) != 0; }

// The firmware's standard headers: vocabulary, maths and algorithms only.
const std::set<std::string> kFirmwareStd = {
    "algorithm", "array",    "bit",     "cfloat",      "climits",         "cmath",       "compare",
    "complex",   "concepts", "cstddef", "cstdint",     "cstdlib",         "cstring",     "initializer_list",
    "iterator",  "limits",   "numbers", "numeric",     "optional",        "span",        "string_view",
    "tuple",     "type_traits", "utility", "variant"};

const std::set<std::string> kHalStd = {"array",   "cstddef", "cstdint",     "limits",
                                       "optional", "span",   "string_view", "type_traits", "utility"};

// Every header of the C++20 standard library (the C ones in their <cxxx> form).
const std::set<std::string> kCxxStd = {
    "algorithm", "any", "array", "atomic", "barrier", "bit", "bitset", "cassert", "cctype", "cerrno", "cfenv",
    "cfloat", "charconv", "chrono", "cinttypes", "climits", "clocale", "cmath", "codecvt", "compare", "complex",
    "concepts", "condition_variable", "coroutine", "csetjmp", "csignal", "cstdarg", "cstddef", "cstdint", "cstdio",
    "cstdlib", "cstring", "ctime", "cuchar", "cwchar", "cwctype", "deque", "exception", "execution", "filesystem",
    "format", "forward_list", "fstream", "functional", "future", "initializer_list", "iomanip", "ios", "iosfwd",
    "iostream", "istream", "iterator", "latch", "limits", "list", "locale", "map", "memory", "memory_resource",
    "mutex", "new", "numbers", "numeric", "optional", "ostream", "queue", "random", "ranges", "ratio", "regex",
    "scoped_allocator", "semaphore", "set", "shared_mutex", "source_location", "span", "sstream", "stack",
    "stdexcept", "stop_token", "streambuf", "string", "string_view", "syncstream", "system_error", "thread",
    "tuple", "type_traits", "typeindex", "typeinfo", "unordered_map", "unordered_set", "utility", "valarray",
    "variant", "vector", "version"};

std::string where(const Include& inc) { return inc.file + ":" + std::to_string(inc.line) + ": " + inc.target; }

TEST(Layering, FirmwareIncludesOnlyFirmwareHalEigenAndPlainStdHeaders) {
  const auto incs = includes_under("firmware");
  ASSERT_FALSE(incs.empty());
  for (const Include& inc : incs) {
    const std::string& t = inc.target;
    const bool ok = (!inc.angle && (starts_with(t, "firmware/") || starts_with(t, "hal/"))) ||
                    (inc.angle && (starts_with(t, "Eigen/") || in(kFirmwareStd, t)));
    EXPECT_TRUE(ok) << where(inc) << " is not on the firmware's allow-list";
  }
}

TEST(Layering, HalIsInterfacesOnly) {
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(TNV_SOURCE_DIR) / "hal"))
    EXPECT_NE(entry.path().extension(), ".cpp") << entry.path();
  const auto incs = includes_under("hal");
  ASSERT_FALSE(incs.empty());
  for (const Include& inc : incs) {
    const bool ok = inc.angle ? in(kHalStd, inc.target) : starts_with(inc.target, "hal/");
    EXPECT_TRUE(ok) << where(inc) << " is not on hal's allow-list";
  }
}

const std::set<std::string> kTextFilePosix = {"fcntl.h", "sys/stat.h", "unistd.h"};

TEST(Layering, EmulatorIncludesOnlyEmulatorHalStdAndToml) {
  const auto incs = includes_under("emulator");
  ASSERT_FALSE(incs.empty());
  for (const Include& inc : incs) {
    const std::string& t = inc.target;
    const bool ok = (!inc.angle && (starts_with(t, "emulator/") || starts_with(t, "hal/"))) ||
                    (inc.angle && (in(kCxxStd, t) || t == "toml++/toml.h")) ||
                    (inc.angle && inc.file.ends_with("emulator/text_file.cpp") && in(kTextFilePosix, t));
    EXPECT_TRUE(ok) << where(inc) << " is not on the emulator's allow-list";
  }
}

TEST(Layering, DriversNeverIncludeFirmware) {
  for (const Include& inc : includes_under("drivers"))
    EXPECT_FALSE(starts_with(inc.target, "firmware/")) << where(inc);
}

// What the tuning library may not use of the standard library: threads and files.
const std::set<std::string> kTuneRefusedStd = {"thread",    "mutex", "shared_mutex", "condition_variable", "future",
                                               "semaphore", "latch", "barrier",      "stop_token",         "iostream",
                                               "fstream",   "filesystem"};

bool tune_may_include(const Include& inc) {
  const std::string& t = inc.target;
  if (!inc.angle) return starts_with(t, "tools/tune/") || starts_with(t, "firmware/") || starts_with(t, "hal/");
  return starts_with(t, "Eigen/") || (in(kCxxStd, t) && !in(kTuneRefusedStd, t));
}

TEST(Layering, TuneIncludesOnlyTuneFirmwareHalEigenAndStd) {
  const auto incs = includes_under("tools/tune");
  ASSERT_FALSE(incs.empty());
  for (const Include& inc : incs) EXPECT_TRUE(tune_may_include(inc)) << where(inc) << " is not on the tuning library's allow-list";
}

// What the scoring library may use: itself, the programmed path, the
// firmware's types, JSON; of the standard library neither threads nor files.
bool score_may_include(const Include& inc) {
  const std::string& t = inc.target;
  if (!inc.angle)
    return starts_with(t, "tools/score/") || starts_with(t, "tools/gcode/") || starts_with(t, "firmware/") ||
           starts_with(t, "hal/");
  return starts_with(t, "Eigen/") || t == "nlohmann/json.hpp" || (in(kCxxStd, t) && !in(kTuneRefusedStd, t));
}

TEST(Layering, ScoreIncludesOnlyScoreGcodeFirmwareHalJsonAndStd) {
  const auto incs = includes_under("tools/score");
  ASSERT_FALSE(incs.empty());
  for (const Include& inc : incs) EXPECT_TRUE(score_may_include(inc)) << where(inc) << " is not on the scoring library's allow-list";
}

// The rig's side of the tree: the emulator, the emulated register bus, the HIL rig.
bool is_rig_side(const std::string& t) {
  return starts_with(t, "emulator/") || starts_with(t, "drivers/emulated/") || starts_with(t, "tools/hil/");
}

TEST(Layering, GcodeNeverIncludesTheEmulatorOrTheRig) {
  const auto incs = includes_under("tools/gcode");
  ASSERT_FALSE(incs.empty());
  for (const Include& inc : incs)
    EXPECT_FALSE(!inc.angle && is_rig_side(inc.target)) << where(inc) << ": tools/gcode may not use the emulator or the HIL rig";
}

bool can_host_may_include(const Include& inc) {
  const std::string& t = inc.target;
  if (inc.angle) return true;  // third-party and standard headers: the link check is layering.can_host_links
  return !starts_with(t, "tools/can_emu/") && !is_rig_side(t);
}

TEST(Layering, CanHostNeverIncludesTheEmulatedNodeOrTheRig) {
  const auto incs = includes_under("tools/can");
  ASSERT_FALSE(incs.empty());
  for (const Include& inc : incs)
    EXPECT_TRUE(can_host_may_include(inc)) << where(inc) << ": tools/can (tnv_can_host) may not use the emulated node or the HIL rig";
}

// tnvctl's own code reaches the emulator and the rig only through the
// emulated node (tools/can_emu/, for --emu).
TEST(Layering, TnvctlReachesTheEmulatorOnlyThroughCanEmu) {
  const auto incs = includes_under("tools/tnvctl");
  ASSERT_FALSE(incs.empty());
  for (const Include& inc : incs)
    EXPECT_FALSE(!inc.angle && is_rig_side(inc.target)) << where(inc) << ": tnvctl uses the emulator only through tools/can_emu";
}

// Guards the guard: the scan sees both include forms and what the lists refuse.
TEST(Layering, TheScanReadsBothIncludeForms) {
  EXPECT_EQ(include_target("#include <vector>"), "vector");
  EXPECT_EQ(include_target("  #  include \"hal/axis.hpp\" // why"), "hal/axis.hpp");
  EXPECT_EQ(include_target("// #include <thread>"), "");
  EXPECT_FALSE(in(kFirmwareStd, "thread"));
  EXPECT_FALSE(in(kFirmwareStd, "vector"));
  EXPECT_FALSE(in(kFirmwareStd, "chrono"));
  EXPECT_FALSE(in(kHalStd, "fstream"));
  EXPECT_FALSE(in(kCxxStd, "unistd.h"));
  EXPECT_FALSE(tune_may_include({"tools/tune/x.cpp", 1, "emulator/scenario.hpp", false}));
  EXPECT_FALSE(tune_may_include({"tools/tune/x.cpp", 1, "tools/hil/hil_rig.hpp", false}));
  EXPECT_FALSE(tune_may_include({"tools/tune/x.cpp", 1, "nlohmann/json.hpp", true}));
  EXPECT_FALSE(tune_may_include({"tools/tune/x.cpp", 1, "thread", true}));
  EXPECT_TRUE(tune_may_include({"tools/tune/x.cpp", 1, "firmware/control/loop_analysis.hpp", false}));
  EXPECT_TRUE(tune_may_include({"tools/tune/x.cpp", 1, "Eigen/Dense", true}));
  EXPECT_FALSE(can_host_may_include({"tools/can/x.cpp", 1, "tools/can_emu/emulated_bus.hpp", false}));
  EXPECT_FALSE(can_host_may_include({"tools/can/x.cpp", 1, "tools/hil/hil_rig.hpp", false}));
  EXPECT_FALSE(can_host_may_include({"tools/can/x.cpp", 1, "emulator/scenario.hpp", false}));
  EXPECT_TRUE(can_host_may_include({"tools/can/x.cpp", 1, "tools/tune/axis_design.hpp", false}));
  EXPECT_FALSE(can_host_may_include({"tools/can/x.cpp", 1, "tools/hil/circle_run.hpp", false}));
  EXPECT_FALSE(can_host_may_include({"tools/can/x.cpp", 1, "emulator/text_file.hpp", false}));
  EXPECT_FALSE(can_host_may_include({"tools/can/x.cpp", 1, "drivers/emulated/emulated_register_bus.hpp", false}));
  EXPECT_TRUE(can_host_may_include({"tools/can/x.cpp", 1, "tools/score/contour_stats.hpp", false}));
  EXPECT_FALSE(score_may_include({"tools/score/x.cpp", 1, "emulator/scenario.hpp", false}));
  EXPECT_FALSE(score_may_include({"tools/score/x.cpp", 1, "tools/hil/hil_rig.hpp", false}));
  EXPECT_FALSE(score_may_include({"tools/score/x.cpp", 1, "drivers/storage/regular_file.hpp", false}));
  EXPECT_FALSE(score_may_include({"tools/score/x.cpp", 1, "fstream", true}));
  EXPECT_TRUE(score_may_include({"tools/score/x.cpp", 1, "tools/gcode/path_distance.hpp", false}));
  EXPECT_TRUE(score_may_include({"tools/score/x.cpp", 1, "nlohmann/json.hpp", true}));
  EXPECT_TRUE(score_may_include({"tools/score/x.cpp", 1, "firmware/motion/motion_limits.hpp", false}));
  EXPECT_TRUE(is_rig_side("emulator/text_file.hpp"));
  EXPECT_FALSE(is_rig_side("drivers/storage/regular_file.hpp"));
}

}  // namespace
