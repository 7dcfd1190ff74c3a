// S4 section 5: what "three in a row" counts, for each reading.
#include <gtest/gtest.h>

#include "firmware/adaptive/boring/variance_perturbation.hpp"

namespace tnv::fw {
namespace {

// Feeds parts of two measurements; returns the part (1-based) and position
// of each reset.
struct Reset {
  int part;
  int position;  // -1: at the end of the part
  bool operator==(const Reset&) const = default;
};

std::vector<Reset> run(BoringResetCount count, const std::vector<std::array<bool, 2>>& parts, int after = 3) {
  VariancePerturbation vp;
  vp.configure(count, after);
  std::vector<Reset> out;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    for (int i = 0; i < 2; ++i)
      if (vp.on_measurement(i, parts[k][static_cast<std::size_t>(i)])) out.push_back({static_cast<int>(k) + 1, i});
    if (vp.on_part_end(parts[k][0] || parts[k][1])) out.push_back({static_cast<int>(k) + 1, -1});
  }
  return out;
}

TEST(VariancePerturbation, MeasurementsCountAcrossPartsInOrder) {
  // Both out, then the first of the next part: three in a row.
  EXPECT_EQ(run(BoringResetCount::measurements, {{true, true}, {true, false}}), (std::vector<Reset>{{2, 0}}));
  // In, out, out, in: the run is broken, never three.
  EXPECT_TRUE(run(BoringResetCount::measurements, {{false, true}, {false, true}, {false, true}, {false, true}}).empty())
      << "the bottom alone out, part after part, never makes three measurements in a row";
}

TEST(VariancePerturbation, PartsCountPartsWithAnyMeasurementOut) {
  EXPECT_EQ(run(BoringResetCount::parts, {{false, true}, {true, false}, {false, true}}),
            (std::vector<Reset>{{3, -1}}));
  EXPECT_TRUE(run(BoringResetCount::parts, {{true, true}, {true, true}, {false, false}, {true, true}}).empty());
}

TEST(VariancePerturbation, PositionsCountEachPositionOnItsOwn) {
  EXPECT_EQ(run(BoringResetCount::positions, {{false, true}, {false, true}, {false, true}}),
            (std::vector<Reset>{{3, 1}}));
  EXPECT_TRUE(run(BoringResetCount::positions, {{true, false}, {false, true}, {true, false}, {false, true}}).empty());
}

TEST(VariancePerturbation, AResetStartsEveryCountAgain) {
  // Out for ever: with measurement counting, a reset every third measurement.
  const std::vector<std::array<bool, 2>> out(6, {true, true});
  EXPECT_EQ(run(BoringResetCount::measurements, out),
            (std::vector<Reset>{{2, 0}, {3, 1}, {5, 0}, {6, 1}}));
  EXPECT_EQ(run(BoringResetCount::parts, out), (std::vector<Reset>{{3, -1}, {6, -1}}));
}

TEST(VariancePerturbation, ResetAfterIsAParameter) {
  EXPECT_EQ(run(BoringResetCount::measurements, {{false, true}}, 1), (std::vector<Reset>{{1, 1}}));
  EXPECT_EQ(run(BoringResetCount::measurements, {{true, true}}, 2), (std::vector<Reset>{{1, 1}}));
  EXPECT_TRUE(run(BoringResetCount::measurements, {{true, true}, {true, true}}, 5).empty());
}

}  // namespace
}  // namespace tnv::fw
