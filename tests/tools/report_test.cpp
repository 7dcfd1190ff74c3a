#include "tools/hil/report.hpp"

#include <gtest/gtest.h>

#include "tools/hil/paper_table3.hpp"
#include "tools/hil/seeded_scenario.hpp"

namespace tnv::hil {
namespace {

std::vector<SweepCell> fake_cells() {
  std::vector<SweepCell> cells;
  double v = 1.0;
  for (const char* s : {"no-cut", "cut-900"}) {
    for (auto k : {fw::ControllerKind::pid, fw::ControllerKind::dvsc, fw::ControllerKind::rdvsc}) {
      SweepCell c;
      c.scenario = s;
      c.controller = k;
      c.averaged = {v, v / 10, v / 5, 100};
      v += 1.0;
      cells.push_back(c);
    }
  }
  return cells;
}

TEST(Report, ResultsJsonCarriesTheDocumentedKeys) {
  const nlohmann::json rows = results_json(fake_cells(), 8);
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_EQ(rows[0]["scenario"], "no-cut");
  EXPECT_EQ(rows[0]["controller"], "pid");
  EXPECT_DOUBLE_EQ(rows[1]["max_um"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(rows[1]["mean_um"].get<double>(), 0.2);
  EXPECT_DOUBLE_EQ(rows[1]["std_um"].get<double>(), 0.4);
  EXPECT_DOUBLE_EQ(rows[2]["paper"]["max_um"].get<double>(), 1.6720);
}

TEST(Report, RatiosAreRdvscOverTheBaseline) {
  const nlohmann::json r = table3_ratios_json(fake_cells());
  ASSERT_EQ(r.size(), 2u);
  EXPECT_DOUBLE_EQ(r[0]["r_pid_max"]["ours"].get<double>(), 3.0 / 1.0);
  EXPECT_DOUBLE_EQ(r[0]["r_dvsc_std"]["ours"].get<double>(), (3.0 / 5) / (2.0 / 5));
  EXPECT_NEAR(r[0]["r_dvsc_max"]["paper"].get<double>(), 1.6720 / 2.4641, 1e-12);
}

TEST(Report, PidGainsArePrintedWithTheRule) {
  const fw::FirmwareConfig config = fw::default_firmware_config();
  const nlohmann::json j = pid_gains_json(config);
  EXPECT_DOUBLE_EQ(j["x"]["kp_per_s"].get<double>(), config.axis[0].pid.kp);
  EXPECT_DOUBLE_EQ(j["y"]["ki_per_s2"].get<double>(), config.axis[1].pid.ki);
  EXPECT_FALSE(j["rule"].get<std::string>().empty());
  const std::string text = table3_text(fake_cells(), 8, config);
  EXPECT_NE(text.find("Kp ="), std::string::npos);
  EXPECT_NE(text.find("R/DVSC"), std::string::npos);
}

TEST(SeededScenario, SeedZeroIsTheScenarioAndOthersSpreadTheEncoderPhase) {
  const emu::Scenario base;
  EXPECT_EQ(seeded(base, 0).encoder.axis_offset_counts[0], base.encoder.axis_offset_counts[0]);
  std::vector<double> fx;
  for (int k = 1; k <= 8; ++k) {
    const emu::Scenario s = seeded(base, k);
    EXPECT_GE(s.encoder.axis_offset_counts[0], 0.0);
    EXPECT_LT(s.encoder.axis_offset_counts[0], 1.0);
    EXPECT_GE(s.cutting.phase_rad, 0.0);
    EXPECT_LT(s.cutting.phase_rad, 2.0 * 3.14159265358979);
    fx.push_back(s.encoder.axis_offset_counts[0]);
  }
  std::sort(fx.begin(), fx.end());
  double widest_gap = 1.0 - fx.back() + fx.front();  // circular
  for (std::size_t i = 1; i < fx.size(); ++i) {
    EXPECT_GT(fx[i] - fx[i - 1], 0.01) << "two seeds share an encoder phase";
    widest_gap = std::max(widest_gap, fx[i] - fx[i - 1]);
  }
  EXPECT_LT(widest_gap, 0.3) << "8 seeds leave a third of the encoder phases unvisited";
}

}  // namespace
}  // namespace tnv::hil
