// The layering is a rule, not a hope (design notes "Layers"): firmware/
// includes only hal/, firmware/, the standard library and Eigen, and none
// of the headers that would let a tick block, sleep, log or do I/O;
// hal/ is interfaces only; emulator/ never includes firmware/ or drivers/.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct Include {
  std::string file;
  int line;
  std::string target;
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
      if (std::string target = include_target(text); !target.empty())
        out.push_back({entry.path().lexically_relative(TNV_SOURCE_DIR).string(), n, std::move(target)});
    }
  }
  return out;
}

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

TEST(Layering, FirmwareIncludesOnlyHalFirmwareStdAndEigen) {
  const std::vector<std::string> forbidden = {"mutex", "thread", "condition_variable", "shared_mutex", "future",
                                              "iostream", "fstream", "cstdio", "chrono", "filesystem", "regex",
                                              "semaphore", "stop_token"};
  const auto incs = includes_under("firmware");
  ASSERT_FALSE(incs.empty());
  for (const Include& inc : incs) {
    const std::string& t = inc.target;
    const std::string where = inc.file + ":" + std::to_string(inc.line) + ": " + t;
    if (t.find('/') != std::string::npos) {
      EXPECT_TRUE(starts_with(t, "hal/") || starts_with(t, "firmware/") || starts_with(t, "Eigen/")) << where;
    } else {
      EXPECT_EQ(std::find(forbidden.begin(), forbidden.end(), t), forbidden.end()) << where;
    }
    EXPECT_FALSE(starts_with(t, "linux/") || starts_with(t, "sys/") || t == "unistd.h" || t == "pthread.h") << where;
  }
}

TEST(Layering, HalIsInterfacesOnly) {
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(TNV_SOURCE_DIR) / "hal"))
    EXPECT_NE(entry.path().extension(), ".cpp") << entry.path();
  for (const Include& inc : includes_under("hal"))
    EXPECT_FALSE(inc.target.find('/') != std::string::npos && !starts_with(inc.target, "hal/"))
        << inc.file << ":" << inc.line << ": " << inc.target;
}

TEST(Layering, EmulatorNeverIncludesFirmwareOrDrivers) {
  for (const Include& inc : includes_under("emulator"))
    EXPECT_FALSE(starts_with(inc.target, "firmware/") || starts_with(inc.target, "drivers/"))
        << inc.file << ":" << inc.line << ": " << inc.target;
}

}  // namespace
