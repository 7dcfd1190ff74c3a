// Two hosts on one emulated node through NodeClient: ownership refusals
// name the owner, and each host's commit applies its own stages only.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "firmware/can/param_table.hpp"
#include "tools/can/node_client.hpp"
#include "tools/can_emu/emulated_bus.hpp"

namespace tnv {
namespace {

namespace can = fw::can;
using can_host::NodeClient;
using can_host::RequestError;

TEST(NodeClientHosts, TwoHostsShareTheNodeWithoutCrossingSetsOrCommands) {
  can_host::EmulatedNodeOptions o;
  o.storage_path = (std::filesystem::temp_directory_path() / ("tnv_hosts_" + std::to_string(::getpid()))).string();
  std::string error;
  auto bus = can_host::EmulatedBus::create(o, error);
  ASSERT_TRUE(bus) << error;
  can_host::ClientOptions one;
  one.host_id = 1;
  can_host::ClientOptions two;
  two.host_id = 2;
  NodeClient a(*bus, 1, one);
  NodeClient b(*bus, 1, two);
  const can::ParamDef& ramp = *can::find_param("motion.circle_ramp_s");
  const can::ParamDef& dwell = *can::find_param("motion.circle_dwell_s");

  a.command(can::CommandCode::enable);  // takes ownership first
  EXPECT_TRUE(a.holds_ownership());
  try {
    b.command(can::CommandCode::disable);
    FAIL() << "host 2 commanded while host 1 owns the node";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.code(), can::ErrorCode::not_owner);
    EXPECT_NE(std::string(e.what()).find("held by host 1"), std::string::npos) << e.what();
  }
  EXPECT_EQ(bus->rig().task.state(), fw::MotionState::holding);

  b.stage(ramp, 0.5);
  b.stage(dwell, 0.25);
  a.stage(ramp, 0.75);
  EXPECT_EQ(a.commit(), 1u) << "host 1 applied its own single stage";
  EXPECT_EQ(a.get(ramp), 0.75);
  a.release_ownership();
  b.take_ownership();
  EXPECT_EQ(b.commit(), 2u) << "host 2's set was kept whole";
  EXPECT_EQ(b.get(ramp), 0.5);
  EXPECT_EQ(b.get(dwell), 0.25);
  EXPECT_EQ(a.replies_discarded() + b.replies_discarded(), 0u);
  b.release_ownership_if_taken();
  EXPECT_FALSE(b.holds_ownership());
  EXPECT_EQ(bus->node().owner(), 0);
  std::error_code ignored;
  std::filesystem::remove(o.storage_path, ignored);
}

}  // namespace
}  // namespace tnv
