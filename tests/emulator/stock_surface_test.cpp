// The stock's height field (emulator/stock_surface.*) and the engagement
// CuttingAtTool reads from it: the reference plant's a_p on uncut stock,
// nothing where the tool has been, a helix turn's pitch, pre-drilled
// holes ([[stock.hole]]) and their keys.
#include "emulator/stock_surface.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "emulator/cutting_at_tool.hpp"
#include "emulator/scenario_file.hpp"
#include "emulator/scenario_validation.hpp"
#include "emulator/substep_timing.hpp"

namespace tnv::emu {
namespace {

constexpr double kTop_mm = -150.0;
constexpr double kRpm = 6000.0;

Scenario plate(double x_max_mm = 100.0, double y_max_mm = 50.0) {
  Scenario s;
  s.stock.enabled = true;
  s.stock.x_min_mm = 0.0;
  s.stock.x_max_mm = x_max_mm;
  s.stock.y_min_mm = 0.0;
  s.stock.y_max_mm = y_max_mm;
  s.tool.diameter_mm = 6.0;
  return s;
}

// Feeds the tool point along a straight line at feed_mm_s, sub-step by
// sub-step; returns the largest a_p seen over the second half of the line.
struct LineResult {
  double depth_max_mm = 0.0;
  double depth_min_mm = 1e9;  // over the second half
};
LineResult feed_line(CuttingAtTool& cut, double x0, double y0, double x1, double y1, double z_mm, double feed_mm_s,
                     std::uint64_t& substep, double rpm = kRpm) {
  const double length = std::hypot(x1 - x0, y1 - y0);
  const auto n = static_cast<std::uint64_t>(std::ceil(length / (feed_mm_s * kSubstep_s)));
  const double vx = feed_mm_s * (x1 - x0) / length, vy = feed_mm_s * (y1 - y0) / length;
  LineResult r;
  for (std::uint64_t k = 0; k <= n; ++k) {
    const double f = static_cast<double>(k) / static_cast<double>(n);
    cut.advance(ToolPointMotion{.x_mm = x0 + f * (x1 - x0), .y_mm = y0 + f * (y1 - y0), .z_mm = z_mm, .vx_mm_s = vx,
                                .vy_mm_s = vy},
                rpm, kRpm, substep_time_s(substep++));
    if (2 * k >= n) {
      r.depth_max_mm = std::max(r.depth_max_mm, cut.depth_mm());
      r.depth_min_mm = std::min(r.depth_min_mm, cut.depth_mm());
    }
  }
  return r;
}

TEST(StockSurface, UncutStockGivesTheReferencePlantsDepthAtEverySubstep) {
  const Scenario s = plate();
  CuttingAtTool cut(s, kSubstep_s);
  const StockBlock block(s.stock);
  std::uint64_t k = 0;
  // From beside the plate into it at a_p = 1 mm, 20 mm/s: every sub-step as the block says.
  const double z = kTop_mm - 1.0;
  const std::uint64_t n = 3'000;  // 30 mm at 20 mm/s... in 10 um sub-steps of 0.2 um
  for (std::uint64_t i = 0; i <= n * 50; ++i) {
    const double x = -10.0 + 20.0 * kSubstep_s * static_cast<double>(i);
    cut.advance(ToolPointMotion{.x_mm = x, .y_mm = 25.0, .z_mm = z, .vx_mm_s = 20.0}, kRpm, kRpm,
                substep_time_s(k++));
    ASSERT_EQ(cut.depth_mm(), block.engagement_mm(x, 25.0, z, s.tool)) << "at x = " << x;
    if (x > 40.0) break;
  }
  EXPECT_EQ(cut.depth_mm(), 1.0);
  EXPECT_EQ(cut.crashes().count(), 0u);
}

TEST(StockSurface, ASecondPassOverTheSameLineMeetsNothing) {
  CuttingAtTool cut(plate(), kSubstep_s);
  std::uint64_t k = 0;
  const LineResult first = feed_line(cut, 10.0, 25.0, 60.0, 25.0, kTop_mm - 2.0, 20.0, k);
  EXPECT_EQ(first.depth_min_mm, 2.0);
  EXPECT_EQ(first.depth_max_mm, 2.0);
  const LineResult back = feed_line(cut, 60.0, 25.0, 10.0, 25.0, kTop_mm - 2.0, 20.0, k);
  EXPECT_EQ(back.depth_max_mm, 0.0) << "the slot is cut";
  // One 0.5 mm deeper sees the 0.5 mm, not the 2.5 below the top.
  const LineResult deeper = feed_line(cut, 10.0, 25.0, 60.0, 25.0, kTop_mm - 2.5, 20.0, k);
  EXPECT_NEAR(deeper.depth_max_mm, 0.5, 1e-12);
  EXPECT_NEAR(deeper.depth_min_mm, 0.5, 1e-12);
  // A slow feed (1 mm/s: a new cell under the disc every few ticks) still reads its depth throughout.
  const LineResult slow = feed_line(cut, 10.0, 30.0, 14.0, 30.0, kTop_mm - 2.5, 1.0, k);
  EXPECT_EQ(slow.depth_min_mm, 2.5) << "never 0 while it moves through material (uncut beside the slot)";
}

TEST(StockSurface, AToolAtRestInItsOwnCutIsNotEngaged) {
  CuttingAtTool cut(plate(), kSubstep_s);
  std::uint64_t k = 0;
  feed_line(cut, 10.0, 25.0, 30.0, 25.0, kTop_mm - 1.0, 20.0, k);
  EXPECT_EQ(cut.depth_mm(), 1.0);
  for (int i = 0; i < 300; ++i) {  // 3 ms at rest, then the spindle stops
    cut.advance(ToolPointMotion{.x_mm = 30.0, .y_mm = 25.0, .z_mm = kTop_mm - 1.0}, kRpm, kRpm, substep_time_s(k++));
  }
  EXPECT_EQ(cut.depth_mm(), 0.0);
  for (int i = 0; i < 300; ++i) {
    cut.advance(ToolPointMotion{.x_mm = 30.0, .y_mm = 25.0, .z_mm = kTop_mm - 1.0}, 0.0, 0.0, substep_time_s(k++));
  }
  EXPECT_EQ(cut.crashes().count(), 0u) << "a spindle stopped in the tool's own cut touches nothing";
  // But plunging from there with the spindle stopped is a crash, however slowly.
  for (int i = 0; i < 100'000; ++i) {  // 1 s at 0.1 mm/s
    cut.advance(ToolPointMotion{.x_mm = 30.0, .y_mm = 25.0, .z_mm = kTop_mm - 1.0 - 1e-6 * i}, 0.0, 0.0,
                substep_time_s(k++));
  }
  EXPECT_EQ(cut.crashes().count(), 1u);
}

TEST(StockSurface, WhatTheToolMetBeforeItRoseIsNotUnderItWhenItComesDownInAHole) {
  Scenario s = plate();
  s.stock.holes = {StockHole{.x_mm = 60.0, .y_mm = 25.0, .diameter_mm = 10.0}};  // through
  CuttingAtTool cut(s, kSubstep_s);
  std::uint64_t k = 0;
  feed_line(cut, 10.0, 25.0, 30.0, 25.0, kTop_mm - 1.0, 20.0, k);
  EXPECT_EQ(cut.depth_mm(), 1.0);
  // Up, across at rapid above the top, and down the hole with the spindle stopped, still moving in XY.
  cut.advance(ToolPointMotion{.x_mm = 30.0, .y_mm = 25.0, .z_mm = kTop_mm + 1.0, .vx_mm_s = 100.0}, 0.0, 0.0,
              substep_time_s(k++));
  for (int i = 0; i < 2'000; ++i) {
    cut.advance(ToolPointMotion{.x_mm = 60.0 + 1e-4 * i, .y_mm = 25.0, .z_mm = kTop_mm + 1.0 - 0.01 * i,
                                .vx_mm_s = 10.0},
                0.0, 0.0, substep_time_s(k++));
    ASSERT_EQ(cut.depth_mm(), 0.0) << i;
  }
  EXPECT_EQ(cut.crashes().count(), 0u);
}

TEST(StockSurface, ASlowPlungeIntoUncutStockWithTheSpindleStoppedIsACrash) {
  CuttingAtTool cut(plate(), kSubstep_s);
  std::uint64_t k = 0;
  for (int i = 0; i < 200'000; ++i) {  // 0.1 mm/s from 0.05 mm above the top
    cut.advance(ToolPointMotion{.x_mm = 50.0, .y_mm = 25.0, .z_mm = kTop_mm + 0.05 - 1e-6 * i}, 0.0, 0.0,
                substep_time_s(k++));
  }
  EXPECT_EQ(cut.crashes().count(), 1u);
  EXPECT_NEAR(cut.crashes().event(0).z_mm, kTop_mm, 1e-6) << "at the first sub-step below the top";
}

TEST(StockSurface, AHelixTurnMeetsAboutItsPitch) {
  CuttingAtTool cut(plate(), kSubstep_s);
  const double cx = 30.0, cy = 25.0, r = 6.35, pitch = 1.27, feed = 10.16;
  const double turn_s = 2.0 * std::numbers::pi * r / feed;
  const auto per_turn = static_cast<std::uint64_t>(std::llround(turn_s / kSubstep_s));
  std::uint64_t k = 0;
  double later_max = 0.0, later_min = 1e9;
  for (int turn = 0; turn < 4; ++turn) {
    for (std::uint64_t i = 0; i < per_turn; ++i) {
      const double f = static_cast<double>(i) / static_cast<double>(per_turn);
      const double a = 2.0 * std::numbers::pi * f;
      const double z = kTop_mm - pitch * (turn + f);
      cut.advance(ToolPointMotion{.x_mm = cx + r * std::cos(a), .y_mm = cy + r * std::sin(a), .z_mm = z,
                                  .vx_mm_s = -feed * std::sin(a), .vy_mm_s = feed * std::cos(a)},
                  kRpm, kRpm, substep_time_s(k++));
      if (turn >= 2) {
        later_max = std::max(later_max, cut.depth_mm());
        later_min = std::min(later_min, cut.depth_mm());
      }
    }
  }
  // The leading edge meets last turn's floor: one pitch (less the ramp's share across the disc).
  EXPECT_LE(later_max, pitch + 0.02);
  EXPECT_GE(later_min, 0.9 * pitch);
  EXPECT_EQ(cut.crashes().count(), 0u);
}

TEST(StockSurface, InsideAPreDrilledHoleThereIsNothing) {
  Scenario s = plate();
  s.stock.holes = {StockHole{.x_mm = 30.0, .y_mm = 25.0, .diameter_mm = 10.0},                   // through
                   StockHole{.x_mm = 60.0, .y_mm = 25.0, .diameter_mm = 10.0, .depth_mm = 15.0}};  // blind
  CuttingAtTool cut(s, kSubstep_s);
  std::uint64_t k = 0;
  // A 6 mm tool at rapid down the through hole, 4 mm... 1.9 mm off its axis, the spindle stopped: no contact.
  for (int i = 0; i < 30'000; ++i) {
    cut.advance(ToolPointMotion{.x_mm = 31.9, .y_mm = 25.0, .z_mm = kTop_mm + 1.0 - 0.01 * i}, 0.0, 0.0,
                substep_time_s(k++));
    ASSERT_EQ(cut.depth_mm(), 0.0) << "at z = " << kTop_mm + 1.0 - 0.01 * i;
  }
  EXPECT_EQ(cut.crashes().count(), 0u);
  // The blind hole: nothing to its floor, the floor below it.
  for (int i = 0; i <= 1'600; ++i) {
    cut.advance(ToolPointMotion{.x_mm = 60.0, .y_mm = 25.0, .z_mm = kTop_mm + 1.0 - 0.01 * i}, 0.0, 0.0,
                substep_time_s(k++));
  }
  EXPECT_EQ(cut.crashes().count(), 0u) << "down to 15 mm";
  for (int i = 0; i < 200; ++i) {
    cut.advance(ToolPointMotion{.x_mm = 60.0, .y_mm = 25.0, .z_mm = kTop_mm - 15.0 - 0.001 * i}, 0.0, 0.0,
                substep_time_s(k++));
  }
  EXPECT_EQ(cut.crashes().count(), 1u) << "below the floor";
  // The surface: the floor and the top beside it; the probe reads the cut surface.
  EXPECT_LT(cut.surface().height_mm(60.0, 25.0), kTop_mm - 15.0) << "the tool took what it met";
  EXPECT_GE(cut.surface().height_mm(60.0, 25.0), kTop_mm - 15.0 - 0.001 * 199);
  EXPECT_EQ(cut.surface().height_mm(60.0, 31.0), kTop_mm);
  EXPECT_FALSE(cut.probe_touches(70.0 - 5.5, 25.0, kTop_mm - 1.0)) << "in the blind hole";
  EXPECT_TRUE(cut.probe_touches(60.0, 32.0, kTop_mm - 1.0)) << "beside it";
  EXPECT_FALSE(cut.probe_touches(60.0, 25.0, kTop_mm - 14.0));
}

TEST(StockSurface, TilesAreAllocatedOnlyWhereTheToolTakesMaterial) {
  Scenario s;  // the whole table
  s.stock.enabled = true;
  StockSurface surface(s.stock);
  EXPECT_EQ(surface.cut(0.0, 0.0, 3.0, kTop_mm + 1.0), kTop_mm) << "above the top: read, not cut";
  EXPECT_EQ(surface.tiles_allocated(), 0u) << "above the top";
  EXPECT_EQ(surface.cut(500.0, -300.0, 3.0, kTop_mm - 1.0), kTop_mm);
  EXPECT_GE(surface.tiles_allocated(), 1u);
  EXPECT_LE(surface.tiles_allocated(), 4u) << "a 6 mm disc spans at most 2 x 2 tiles of 6.4 mm";
  EXPECT_EQ(surface.highest_mm(500.0, -300.0, 3.0), kTop_mm - 1.0);
  EXPECT_EQ(surface.height_mm(500.0, -300.0), kTop_mm - 1.0);
  EXPECT_EQ(surface.height_mm(-500.0, 300.0), kTop_mm) << "untouched";
}

// The cells a cut lowers are exactly those whose square (clipped to the
// stock's rectangle) overlaps the disc, and it returns the highest of them
// as they were: checked cell by cell against the rule itself, for discs of
// every size across the rectangle's edges (which do not fall on the grid),
// off it, and on a stock without edges (the whole table).
TEST(StockSurface, ACutLowersExactlyTheCellsUnderItsDiscAndReturnsTheHighestOfThem) {
  struct Plate {
    double x_min, x_max, y_min, y_max;  // the rectangle (infinite: no edge)
    double origin_x, origin_y;          // the grid's corner: the low edge, or 0 without one
    int i0, j0, nx, ny;                 // the cells the model holds: [i0, i0 + nx) x [j0, j0 + ny)
  };
  constexpr double kNoEdge = std::numeric_limits<double>::infinity();
  for (const Plate p : {Plate{0.03, 6.27, -1.05, 4.4, 0.03, -1.05, 0, 0, 63, 55},
                        Plate{-kNoEdge, kNoEdge, -kNoEdge, kNoEdge, 0.0, 0.0, -45, -55, 150, 150}}) {
    StockParams params;
    params.enabled = true;
    params.x_min_mm = p.x_min;
    params.x_max_mm = p.x_max;
    params.y_min_mm = p.y_min;
    params.y_max_mm = p.y_max;
    StockSurface surface(params);
    std::vector<double> model(static_cast<std::size_t>(p.nx * p.ny), params.top_mm);
    const auto lo = [](double origin, double edge, int i) { return std::max(origin + static_cast<double>(i) * StockSurface::kCellMm, edge); };
    const auto hi = [](double origin, double edge, int i) { return std::min(origin + static_cast<double>(i + 1) * StockSurface::kCellMm, edge); };
    std::mt19937 rng(29);
    std::uniform_real_distribution<double> at(-1.5, 7.5), radius(0.02, 2.5), depth(0.0, 3.0);
    for (int cut = 0; cut < 250; ++cut) {
      const double x = at(rng), y = at(rng) - 1.0, r = radius(rng), z = params.top_mm - depth(rng);
      double expected = -kNoEdge;
      std::vector<double> after = model;
      for (int j = p.j0; j < p.j0 + p.ny; ++j) {
        for (int i = p.i0; i < p.i0 + p.nx; ++i) {
          const double xl = lo(p.origin_x, p.x_min, i), xh = hi(p.origin_x, p.x_max, i);
          const double yl = lo(p.origin_y, p.y_min, j), yh = hi(p.origin_y, p.y_max, j);
          if (!(xl < xh) || !(yl < yh)) continue;  // off the rectangle
          const double dx = std::max({xl - x, 0.0, x - xh}), dy = std::max({yl - y, 0.0, y - yh});
          double& h = after[static_cast<std::size_t>((j - p.j0) * p.nx + i - p.i0)];
          if (dx * dx + dy * dy < r * r) {
            expected = std::max(expected, h);
            h = std::min(h, z);
          }
        }
      }
      ASSERT_EQ(surface.cut(x, y, r, z), expected) << "cut " << cut << " at (" << x << ", " << y << ") r " << r;
      model = after;
      for (int j = p.j0; j < p.j0 + p.ny; ++j) {
        for (int i = p.i0; i < p.i0 + p.nx; ++i) {
          const double xl = lo(p.origin_x, p.x_min, i), xh = hi(p.origin_x, p.x_max, i);
          const double yl = lo(p.origin_y, p.y_min, j), yh = hi(p.origin_y, p.y_max, j);
          if (!(xl < xh) || !(yl < yh)) continue;
          ASSERT_EQ(surface.height_mm(0.5 * (xl + xh), 0.5 * (yl + yh)), model[static_cast<std::size_t>((j - p.j0) * p.nx + i - p.i0)])
              << "cell " << i << ", " << j << " after cut " << cut;
        }
      }
    }
  }
}

TEST(StockSurface, HoleKeysAreParsed) {
  const ScenarioResult r = parse_scenario_text(
      "[stock]\nenabled = true\n[[stock.hole]]\nx_mm = 1\ny_mm = 2.5\ndiameter_mm = 5\ndepth_mm = 15\n"
      "[[stock.hole]]\nx_mm = -3\ny_mm = 4\ndiameter_mm = 20\nthrough = true\n",
      "h.toml");
  ASSERT_TRUE(r.scenario) << r.error;
  ASSERT_EQ(r.scenario->stock.holes.size(), 2u);
  EXPECT_EQ(r.scenario->stock.holes[0].x_mm, 1.0);
  EXPECT_EQ(r.scenario->stock.holes[0].y_mm, 2.5);
  EXPECT_EQ(r.scenario->stock.holes[0].diameter_mm, 5.0);
  EXPECT_EQ(r.scenario->stock.holes[0].depth_mm, 15.0);
  EXPECT_TRUE(std::isinf(r.scenario->stock.holes[1].depth_mm)) << "through";
}

struct BadHole {
  const char* what;
  const char* hole;      // the [[stock.hole]] table's lines
  const char* expected;  // the error after "h.toml:"
};

class StockHoleErrors : public ::testing::TestWithParam<BadHole> {};

TEST_P(StockHoleErrors, RefusedNamingTheKey) {
  const BadHole& c = GetParam();
  const ScenarioResult r =
      parse_scenario_text(std::string("[stock]\nenabled = true\n[[stock.hole]]\n") + c.hole, "h.toml");
  EXPECT_FALSE(r.scenario) << c.what << ": accepted";
  EXPECT_EQ(r.error, std::string("h.toml:") + c.expected) << c.what;
}

INSTANTIATE_TEST_SUITE_P(
    EveryKey, StockHoleErrors,
    ::testing::Values(
        BadHole{"no diameter", "x_mm = 1\ny_mm = 2\nthrough = true\n", "3:1: stock.hole[0].diameter_mm: required"},
        BadHole{"no x", "y_mm = 2\ndiameter_mm = 5\nthrough = true\n", "3:1: stock.hole[0].x_mm: required"},
        BadHole{"neither depth nor through", "x_mm = 1\ny_mm = 2\ndiameter_mm = 5\n",
                "3:1: stock.hole[0].depth_mm: give depth_mm or through = true, one of them"},
        BadHole{"both", "x_mm = 1\ny_mm = 2\ndiameter_mm = 5\ndepth_mm = 3\nthrough = true\n",
                "3:1: stock.hole[0].through: give depth_mm or through = true, one of them"},
        BadHole{"through false", "x_mm = 1\ny_mm = 2\ndiameter_mm = 5\nthrough = false\n",
                "7:1: stock.hole[0].through: only through = true is meaningful (else give depth_mm)"},
        BadHole{"zero diameter", "x_mm = 1\ny_mm = 2\ndiameter_mm = 0\nthrough = true\n",
                "6:1: stock.hole[0].diameter_mm: must be in (0, 500] (a hole's diameter)"},
        BadHole{"negative depth", "x_mm = 1\ny_mm = 2\ndiameter_mm = 5\ndepth_mm = -1\n",
                "7:1: stock.hole[0].depth_mm: must be in (0, 2000] (a depth below the stock top)"},
        BadHole{"far away", "x_mm = 1e6\ny_mm = 2\ndiameter_mm = 5\nthrough = true\n",
                "4:1: stock.hole[0].x_mm: must be in (-1000, 1000] (machine coordinates)"},
        BadHole{"a string", "x_mm = \"1\"\ny_mm = 2\ndiameter_mm = 5\nthrough = true\n",
                "4:1: stock.hole[0].x_mm: expected a number, got a string"},
        BadHole{"unknown key", "x_mm = 1\ny_mm = 2\ndiameter_mm = 5\nthrough = true\nradius_mm = 2\n",
                "8:1: stock.hole[0].radius_mm: unknown key"}),
    [](const ::testing::TestParamInfo<BadHole>& param) {
      std::string name = param.param.what;
      for (char& ch : name) {
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      }
      return name;
    });

TEST(StockSurface, AHoleBuiltInCodeIsCheckedLikeOneRead) {
  Scenario s = plate();
  s.stock.holes = {StockHole{.x_mm = 1.0, .y_mm = 2.0, .diameter_mm = 5.0}};
  EXPECT_EQ(validate_scenario(s), "");
  s.stock.holes.push_back(StockHole{.x_mm = 1.0, .y_mm = 2.0, .diameter_mm = 0.0});
  EXPECT_NE(validate_scenario(s).find("stock.hole[1].diameter_mm"), std::string::npos) << validate_scenario(s);
  s.stock.holes[1] = StockHole{.x_mm = 1.0, .y_mm = 2.0, .diameter_mm = 5.0, .depth_mm = 0.0};
  EXPECT_NE(validate_scenario(s).find("stock.hole[1].depth_mm"), std::string::npos) << validate_scenario(s);
}

TEST(StockSurface, ANotArrayHoleIsRefused) {
  const ScenarioResult r = parse_scenario_text("[stock]\nhole = 3\n", "h.toml");
  EXPECT_FALSE(r.scenario);
  EXPECT_EQ(r.error, "h.toml:2:1: stock.hole: expected an array of tables ([[stock.hole]]), got an integer");
}

}  // namespace
}  // namespace tnv::emu
