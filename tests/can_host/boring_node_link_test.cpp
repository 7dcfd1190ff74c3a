// Boring on the board, end to end: every part of the S4 scenarios through
// the emulated node over CAN gives bit for bit the infeeds of the planner
// called in process at the node's resolution; and a node powered down
// between two parts (its image saved) continues with identical infeeds.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <memory>
#include <string>

#include "emulator/boring_process.hpp"
#include "tools/can/boring_node_link.hpp"
#include "tools/can_emu/emulated_bus.hpp"
#include "tools/hil/boring_direct_link.hpp"
#include "tools/hil/boring_run.hpp"

namespace tnv::can_host {
namespace {

std::string temp_params(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("tnv_boring_link_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

std::unique_ptr<EmulatedBus> emulated_node(const std::string& path) {
  EmulatedNodeOptions o;
  o.storage_path = path;
  std::string error;
  std::unique_ptr<EmulatedBus> bus = EmulatedBus::create(o, error);
  EXPECT_TRUE(bus) << error;
  return bus;
}

struct S4Case {
  const char* name;
  double sigma_mm, alpha0;
  fw::BoringGainForm form;
  fw::BoringResetCount count;
  int reset_after;
};

TEST(BoringNodeLink, EveryPartOfTheS4ScenariosGetsTheDirectPlannersInfeedsBitForBit) {
  const std::string path = temp_params("equal");
  std::unique_ptr<EmulatedBus> bus = emulated_node(path);
  ASSERT_TRUE(bus);
  NodeClient client(*bus, bus->node_id());
  BoringNodeLink node(client);
  hil::BoringDirectLink direct;
  const S4Case cases[] = {
      {"Fig. 3", 0.016231, 0.5, fw::BoringGainForm::normalised, fw::BoringResetCount::measurements, 3},
      {"Fig. 4 normalised", 0.005, 1.0, fw::BoringGainForm::normalised, fw::BoringResetCount::measurements, 3},
      {"Fig. 4 printed", 0.005, 1.0, fw::BoringGainForm::printed, fw::BoringResetCount::measurements, 3},
      {"Fig. 4 kalman, parts", 0.005, 1.0, fw::BoringGainForm::kalman, fw::BoringResetCount::parts, 3},
      {"positions, reset after 1", 0.016231, 0.5, fw::BoringGainForm::normalised, fw::BoringResetCount::positions, 1},
  };
  int resets = 0;
  for (const S4Case& c : cases) {
    hil::BoringRunRequest r = hil::paper_boring_request(c.sigma_mm, c.alpha0);
    r.planner.gain_form = c.form;
    r.planner.reset_count = c.count;
    r.planner.reset_after = c.reset_after;
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      SCOPED_TRACE(std::string(c.name) + ", seed " + std::to_string(seed));
      const hil::BoringRunResult a = hil::run_boring(r, seed, node);
      const hil::BoringRunResult b = hil::run_boring(r, seed, direct);
      ASSERT_TRUE(a.error.empty()) << a.error;
      ASSERT_TRUE(b.error.empty()) << b.error;
      ASSERT_EQ(a.parts.size(), 30u);
      ASSERT_EQ(b.parts.size(), 30u);
      for (std::size_t k = 0; k < a.parts.size(); ++k) {
        const hil::BoringPartRecord& x = a.parts[k];
        const hil::BoringPartRecord& y = b.parts[k];
        for (std::size_t i = 0; i < 2; ++i) {
          EXPECT_EQ(x.positions[i].infeed_mm_rev, y.positions[i].infeed_mm_rev) << "part " << k + 1 << " position " << i;
          EXPECT_EQ(x.positions[i].infeed_limited, y.positions[i].infeed_limited) << "part " << k + 1;
        }
        EXPECT_EQ(x.reset, y.reset) << "part " << k + 1;
        EXPECT_EQ(x.resets, y.resets) << "part " << k + 1;
        EXPECT_EQ(x.out_of_band, y.out_of_band) << "part " << k + 1;
        EXPECT_EQ(x.bad, y.bad) << "part " << k + 1;
        // The estimates come back as the f32 parameters bore.*_hat.
        EXPECT_EQ(x.alpha_hat, static_cast<double>(static_cast<float>(y.alpha_hat))) << "part " << k + 1;
        EXPECT_EQ(x.beta_hat, static_cast<double>(static_cast<float>(y.beta_hat))) << "part " << k + 1;
        EXPECT_EQ(x.c_hat_mm, static_cast<double>(static_cast<float>(y.c_hat_mm))) << "part " << k + 1;
      }
      EXPECT_EQ(a.bad_parts, b.bad_parts);
      EXPECT_EQ(a.resets, b.resets);
      // Not only the infeeds on their grid: what the two planners learned is the same to the last bit.
      ASSERT_NE(direct.planner(), nullptr);
      EXPECT_TRUE(bus->node().settings().bore_state.planner == direct.planner()->state());
      resets += a.resets;
    }
  }
  EXPECT_GT(resets, 20) << "the runs went through variance perturbations";
  EXPECT_GE(bus->node().settings().bore_state.planner.parts, 30);
  std::filesystem::remove(path);
}

// Part `part` of S4's process (seed 7), cut with `infeed`: the two readings.
std::vector<double> gauge_part(emu::BoringProcess& process, int part, const BoreInfeed& infeed) {
  return {process.measure_bore_error_mm(part, infeed.infeed_top_mm_rev, 40.0),
          process.measure_bore_error_mm(part, infeed.infeed_bottom_mm_rev, 310.0)};
}

TEST(BoringNodeLink, ANodePoweredDownBetweenTwoPartsContinuesWithIdenticalInfeeds) {
  const std::string path = temp_params("restart");
  const std::string twin_path = temp_params("twin");
  std::filesystem::remove(path);
  std::filesystem::remove(twin_path);
  hil::BoringRunRequest r = hil::paper_boring_request(0.016231, 0.5);
  std::vector<BoreInfeed> uninterrupted;
  fw::BoringStationState uninterrupted_state;
  {
    std::unique_ptr<EmulatedBus> bus = emulated_node(twin_path);
    ASSERT_TRUE(bus);
    NodeClient client(*bus, bus->node_id());
    BoringNodeLink link(client);
    ASSERT_EQ(link.start(r.planner, r.positions_mm), "");
    emu::BoringProcess process(emu::paper_boring_process(0.016231, 7, 11, 21));
    BoreInfeed told = client.bore(fw::can::BoreOp::query);
    for (int part = 1; part <= 30; ++part) {
      const std::vector<double> g = gauge_part(process, part, told);
      told = client.bore(fw::can::BoreOp::record, static_cast<std::uint16_t>(part), g[0], g[1]);
      uninterrupted.push_back(told);
    }
    uninterrupted_state = bus->node().settings().bore_state;
  }
  emu::BoringProcess process(emu::paper_boring_process(0.016231, 7, 11, 21));
  BoreInfeed told;
  {
    std::unique_ptr<EmulatedBus> bus = emulated_node(path);
    ASSERT_TRUE(bus);
    NodeClient client(*bus, bus->node_id());
    BoringNodeLink link(client);
    ASSERT_EQ(link.start(r.planner, r.positions_mm), "");
    told = client.bore(fw::can::BoreOp::query);
    for (int part = 1; part <= 12; ++part) {
      const std::vector<double> g = gauge_part(process, part, told);
      told = client.bore(fw::can::BoreOp::record, static_cast<std::uint16_t>(part), g[0], g[1]);
    }
    client.command(fw::can::CommandCode::save_params);
  }  // power down after part 12: part 13 is on the machine with the infeeds told
  std::unique_ptr<EmulatedBus> bus = emulated_node(path);
  ASSERT_TRUE(bus);
  EXPECT_EQ(bus->startup_note(), "") << "the image loaded";
  NodeClient client(*bus, bus->node_id());
  const BoreInfeed resumed = client.bore(fw::can::BoreOp::query);
  EXPECT_EQ(resumed.infeed_top_mm_rev, told.infeed_top_mm_rev);
  EXPECT_EQ(resumed.infeed_bottom_mm_rev, told.infeed_bottom_mm_rev);
  EXPECT_EQ(client.get(*fw::can::find_param("bore.parts")), 12.0);
  told = resumed;
  for (int part = 13; part <= 30; ++part) {
    const std::vector<double> g = gauge_part(process, part, told);
    told = client.bore(fw::can::BoreOp::record, static_cast<std::uint16_t>(part), g[0], g[1]);
    const BoreInfeed& same = uninterrupted[static_cast<std::size_t>(part - 1)];
    EXPECT_EQ(told.infeed_top_mm_rev, same.infeed_top_mm_rev) << "after part " << part;
    EXPECT_EQ(told.infeed_bottom_mm_rev, same.infeed_bottom_mm_rev) << "after part " << part;
    EXPECT_EQ(told.flags, same.flags) << "part " << part;
  }
  EXPECT_TRUE(bus->node().settings().bore_state == uninterrupted_state) << "learned the same, to the last bit";
  std::filesystem::remove(path);
  std::filesystem::remove(path + ".prev");
  std::filesystem::remove(twin_path);
}

}  // namespace
}  // namespace tnv::can_host
