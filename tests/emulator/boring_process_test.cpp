// The S4 process the boring planner is judged against.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "emulator/boring_process.hpp"

namespace tnv::emu {
namespace {

TEST(BoringProcess, TableOneIsConsistentAndTheSetsChangeAtTheGivenParts) {
  BoringProcess p(paper_boring_process(0.016231, 1));
  // Table 1: 1/K = 28.111 mm^-1, gamma = 0.9777, a = 2.5 mm, C = 0.0871 mm.
  EXPECT_NEAR(std::pow(2.5, 0.9777) / 28.111, 0.0871, 0.5e-4) << "Table 1's K, gamma, a give its C to 4 digits";
  EXPECT_NEAR(p.parameters(1).k_mm * std::pow(2.5, 0.9777), 0.0871, 1e-12) << "K = C / a^gamma";
  EXPECT_NEAR(p.c_mm(1), 0.0871, 1e-12);
  EXPECT_EQ(p.parameters(10).alpha, 0.5025);
  EXPECT_EQ(p.parameters(11).alpha, 0.7);
  EXPECT_NEAR(p.c_mm(20), 0.15, 1e-12);
  EXPECT_EQ(p.parameters(21).beta, 0.5);
  EXPECT_NEAR(p.c_mm(1000), 0.075, 1e-12);
  BoringProcess unchanged(unchanged_boring_process(0.016231, 1));
  EXPECT_EQ(unchanged.parameters(1000).alpha, 0.5025);
}

TEST(BoringProcess, DeflectionIsEquationOneAndTheOptimalInfeedHitsThePreset) {
  BoringProcess p(paper_boring_process(0.0, 1));
  EXPECT_NEAR(p.deflection_mm(1, 0.5, 40.0), 0.0871 * std::pow(0.5, 0.5025) * std::pow(40.0, 0.2676), 1e-12);
  for (int part : {1, 11, 21})
    for (double l : {40.0, 175.0, 310.0})
      EXPECT_NEAR(p.deflection_mm(part, p.optimal_infeed_mm_rev(part, l), l), 0.1165, 1e-12)
          << "part " << part << ", L = " << l << " mm";
}

TEST(BoringProcess, GaugeReadsEquationElevenWithSeededNoiseOfTheGivenSigma) {
  const double sigma = 0.016231;
  BoringProcess a(paper_boring_process(sigma, 42));
  BoringProcess b(paper_boring_process(sigma, 42));
  BoringProcess c(paper_boring_process(sigma, 43));
  const double d = a.deflection_mm(1, 0.2, 100.0);
  constexpr int n = 40'000;
  double sum = 0.0, sum_sq = 0.0;
  bool differs = false;
  for (int i = 0; i < n; ++i) {
    const double ea = a.measure_bore_error_mm(1, 0.2, 100.0);
    ASSERT_EQ(ea, b.measure_bore_error_mm(1, 0.2, 100.0)) << "same seed, same numbers";
    differs = differs || ea != c.measure_bore_error_mm(1, 0.2, 100.0);
    const double e = ea - 2.0 * 0.5 * (d - 0.1165);  // phi = 60 deg: 2 cos phi = 1
    sum += e;
    sum_sq += e * e;
  }
  EXPECT_TRUE(differs);
  const double mean = sum / n;
  const double sd = std::sqrt(sum_sq / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 4.0 * sigma / std::sqrt(n)) << "mm";
  EXPECT_NEAR(sd, sigma, 0.02 * sigma) << "mm";
  BoringProcess exact(paper_boring_process(0.0, 1));
  EXPECT_NEAR(exact.measure_bore_error_mm(1, 0.2, 100.0), d - 0.1165, 1e-15) << "sigma 0: the gauge is exact";
}

// What the paper calls the small change (part 21) is small only against
// sigma_d = 0.016231: cut with the schedule that is optimal for the second
// set, the third set leaves the top in band and the bottom out of band at
// sigma_d = 0.005. This is why no "three in a row" rule can reset at once
// there (docs/reproduction-s4.md).
TEST(BoringProcess, TheSmallChangeIsOutOfBandOnlyAtTheBottomWhenSigmaIsFiveMicrons) {
  BoringProcess p(paper_boring_process(0.0, 1));
  const double top = p.deflection_mm(21, p.optimal_infeed_mm_rev(20, 40.0), 40.0);
  const double bottom = p.deflection_mm(21, p.optimal_infeed_mm_rev(20, 310.0), 310.0);
  EXPECT_NEAR(top, 0.1078, 1e-4) << "mm";
  EXPECT_NEAR(bottom, 0.1488, 1e-4) << "mm";
  EXPECT_LT(std::fabs(top - 0.1165), 3 * 0.005);
  EXPECT_GT(std::fabs(bottom - 0.1165), 3 * 0.005);
  EXPECT_LT(std::fabs(bottom - 0.1165), 3 * 0.016231) << "and in band at the paper's sigma";
  // No bottom infeed is in band for both: the largest S that keeps the
  // third set at or below d0 + 3 sigma deflects below d0 - 3 sigma under the second.
  const double s_max = std::pow((0.1165 + 3 * 0.005) / (p.c_mm(21) * std::pow(310.0, 0.5)), 1.0 / 0.6);
  EXPECT_NEAR(p.deflection_mm(21, s_max, 310.0), 0.1165 + 3 * 0.005, 1e-12);
  EXPECT_LT(p.deflection_mm(20, s_max, 310.0), 0.1165 - 3 * 0.005) << "mm, second set at S = " << s_max;
  // The large change (part 11) is out of band at both positions for both sigmas.
  for (double l : {40.0, 310.0})
    EXPECT_GT(p.deflection_mm(11, p.optimal_infeed_mm_rev(10, l), l) - 0.1165, 3 * 0.016231) << "L = " << l;
}

// A bench's bore gauge ([noise] bore_gauge_*): its repeatability adds to the
// reading from a stream of its own, so the process noise e is drawn as
// before, and the reading lands on the gauge's step.
TEST(BoringProcess, ABenchGaugeAddsItsOwnNoiseAndStepToTheReading) {
  const BoringProcessConfig paper = paper_boring_process(0.016231, 7);
  BoringProcessConfig stepped = paper;
  stepped.gauge_resolution_mm = 0.001;
  BoringProcessConfig noisy = paper;
  noisy.gauge_noise_mm_rms = 0.001;
  noisy.gauge_seed = 3;
  BoringProcess exact(paper), step(stepped), gauge(noisy);
  double sum_sq = 0.0;
  constexpr int kReadings = 4000;
  for (int i = 0; i < kReadings; ++i) {
    const double e = exact.measure_bore_error_mm(1, 0.5, 175.0);
    const double r = step.measure_bore_error_mm(1, 0.5, 175.0);
    ASSERT_EQ(r, 0.001 * std::round(e / 0.001)) << "reading " << i << ": on the 1 um step of the exact one";
    const double g = gauge.measure_bore_error_mm(1, 0.5, 175.0);
    sum_sq += (g - e) * (g - e);
  }
  EXPECT_NEAR(std::sqrt(sum_sq / kReadings), 0.001, 0.05e-3) << "gauge noise, mm rms on the bore error";
}

TEST(BoringProcess, InvalidConfigurationsAreRefusedNamingTheField) {
  const auto error_of = [](auto mutate) {
    BoringProcessConfig c = paper_boring_process(0.01, 1);
    mutate(c);
    return validate_boring_process(c);
  };
  EXPECT_EQ(error_of([](BoringProcessConfig&) {}), "");
  EXPECT_NE(error_of([](auto& c) { c.sets.clear(); }).find("sets"), std::string::npos);
  EXPECT_NE(error_of([](auto& c) { c.sets[0].first_part = 2; }).find("sets[0].first_part"), std::string::npos);
  EXPECT_NE(error_of([](auto& c) { c.sets[2].first_part = 5; }).find("sets[2].first_part"), std::string::npos);
  EXPECT_NE(error_of([](auto& c) { c.sets[1].alpha = std::nan(""); }).find("sets[1].alpha"), std::string::npos);
  EXPECT_NE(error_of([](auto& c) { c.sets[0].k_mm = 0.0; }).find("sets[0].k_mm"), std::string::npos);
  EXPECT_NE(error_of([](auto& c) { c.sigma_d_mm = -1.0; }).find("sigma_d_mm"), std::string::npos);
  EXPECT_NE(error_of([](auto& c) { c.depth_of_cut_mm = std::numeric_limits<double>::infinity(); }).find("depth_of_cut_mm"),
            std::string::npos);
  EXPECT_NE(error_of([](auto& c) { c.force_angle_deg = 90.0; }).find("force_angle_deg"), std::string::npos);
  EXPECT_NE(error_of([](auto& c) { c.gauge_noise_mm_rms = -1e-3; }).find("gauge_noise_mm_rms"), std::string::npos);
  EXPECT_NE(error_of([](auto& c) { c.gauge_resolution_mm = std::nan(""); }).find("gauge_resolution_mm"),
            std::string::npos);
  BoringProcessConfig bad = paper_boring_process(0.01, 1);
  bad.sigma_d_mm = std::nan("");
  EXPECT_THROW(BoringProcess{bad}, std::invalid_argument);
}

}  // namespace
}  // namespace tnv::emu
