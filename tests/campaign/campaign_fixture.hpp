#pragma once
// A fresh directory per test and a short circle (a 2 mm circle at 20 mm/s,
// 0.6 s of motion) so a campaign of a few runs takes well under a second.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tools/campaign/campaign_file.hpp"
#include "tools/campaign/manifest.hpp"

namespace tnv::campaign::test {

inline constexpr const char* kShortScenario =
    "name = \"short\"\n"
    "[circle]\n"
    "radius_mm = 2.0\n"
    "feed_mm_s = 20.0\n"
    "dwell_s = 0.05\n";

// The issue's example campaign (docs/campaigns.md "The campaign file"):
// a circle, R-DVSC+DDC on no-cut, 200 runs, seed 7, three inputs varied
// (lines 7-9). A test puts in its own controllers, scenario, run count or
// sampling (a sampling line comes before [vary]: the inputs move to 8-10).
struct ExampleCampaign {
  std::string controllers = R"(["rdvsc"])";
  std::string scenario = "no-cut";
  int runs = 200;
  std::string sampling;  // empty: the file's default
};

inline std::string example_campaign(const ExampleCampaign& c = {}) {
  std::string text = "experiment = \"circle\"\ncontrollers = " + c.controllers + "\nscenario = \"" + c.scenario +
                     "\"\nruns = " + std::to_string(c.runs) + "\nseed = 7\n";
  if (!c.sampling.empty()) text += "sampling = \"" + c.sampling + "\"\n";
  return text +
         "[vary]\n"
         "\"plant.x.coulomb_mm_s\" = { normal = [1.5, 0.3] }\n"
         "\"plant.y.gain\" = { uniform = [0.8, 1.2] }\n"
         "\"x.sliding.gamma\" = { uniform = [0.35, 0.45] }\n";
}

inline std::string read_all(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void write_all(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << text;
}

class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("tnv_campaign_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Writes `text` as work/study.toml, plans it into `out` and loads the
// manifest back (each step's error reported as a test failure).
inline Manifest plan_text(const std::filesystem::path& work, const std::string& text, const std::filesystem::path& out) {
  write_all(work / "study.toml", text);
  const CampaignResult spec = load_campaign_file((work / "study.toml").string());
  EXPECT_TRUE(spec.spec) << spec.error;
  if (!spec.spec) return {};
  const PlanResult p = plan_campaign(*spec.spec, text, out);
  EXPECT_TRUE(p.ok) << p.error;
  ManifestResult m = load_manifest(out);
  EXPECT_TRUE(m.manifest) << m.error;
  return m.manifest ? *m.manifest : Manifest{};
}

}  // namespace tnv::campaign::test
