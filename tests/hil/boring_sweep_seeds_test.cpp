// A sweep split over processes (`tnv-hil boring --first-seed K --seeds N`):
// seeds K .. K+N-1 each run once, in order, the first one kept as seed1, and
// the report says which seeds it holds.
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "tools/hil/boring_report.hpp"
#include "tools/hil/boring_sweep.hpp"

namespace tnv::hil {
namespace {

TEST(BoringSweepSeeds, AFirstSeedRunsThatRangeAndTheReportNamesIt) {
  BoringRunRequest r = paper_boring_request(0.016231, 0.5);
  r.parts = 12;
  std::vector<std::uint64_t> seen;
  const BoringSeedRun run_seed = [&](std::uint64_t seed) {
    seen.push_back(seed);
    return run_boring(r, seed);  // the planner in process, at the node's resolution
  };
  const BoringSweepResult s = run_boring_sweep(r, 3, "test", run_seed, {}, 7);
  EXPECT_EQ(seen, (std::vector<std::uint64_t>{7, 8, 9}));
  EXPECT_EQ(s.first_seed, 7u);
  EXPECT_EQ(s.seeds, 3);
  EXPECT_EQ(s.seed1.seed, 7u) << "the first seed's run is the one kept";
  EXPECT_NE(boring_sweep_text(r, s).find("seeds 7..9"), std::string::npos);
  EXPECT_EQ(boring_sweep_json(r, s)["settings"]["first_seed"], 7);
  // From seed 1 the report is as it was (no first_seed field).
  const BoringSweepResult from1 = run_boring_sweep(r, 1, "test", run_seed, {});
  EXPECT_FALSE(boring_sweep_json(r, from1)["settings"].contains("first_seed"));
  EXPECT_THROW(run_boring_sweep(r, 1, "test", run_seed, {}, 0), std::invalid_argument);
}

}  // namespace
}  // namespace tnv::hil
