// The emulated node with two stored generations (drivers::FileParamStorage):
// a damaged current image starts the node with the previous saved set, not
// the defaults and not half of either, and says so: the start-up note and
// the heartbeat's storage_fault bit, as a real node would over CAN.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "firmware/can/param_table.hpp"
#include "tools/can/node_client.hpp"
#include "tools/can_emu/emulated_bus.hpp"

namespace tnv {
namespace {

namespace can = fw::can;
using can_host::EmulatedBus;
using can_host::Micros;
using can_host::NodeClient;

std::unique_ptr<EmulatedBus> make_fallback_bus(const std::string& storage) {
  can_host::EmulatedNodeOptions o;
  o.storage_path = storage;
  std::string error;
  auto bus = EmulatedBus::create(o, error);
  EXPECT_TRUE(bus) << error;
  return bus;
}

const can::ParamDef& x_gamma_param() { return *can::find_param("x.sliding.gamma"); }

void damage(const std::string& path, std::streamoff at) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(at);
  const char c = static_cast<char>(f.get());
  f.seekp(at);
  f.put(static_cast<char>(c ^ 0x10));
}

// A fresh storage file in the temp directory with two saves on it: gamma
// 0.25 (generation 1, then in .prev) and 0.5 (generation 2, current).
std::string two_saves(const char* prefix) {
  std::string file = prefix;
  file.append(std::to_string(::getpid())).append(".params");
  const std::string storage = (std::filesystem::temp_directory_path() / file).string();
  std::filesystem::remove(storage);
  std::filesystem::remove(storage + ".prev");
  auto bus = make_fallback_bus(storage);
  NodeClient client(*bus, 1);
  client.set(x_gamma_param(), 0.25);
  EXPECT_EQ(client.command(can::CommandCode::save_params).result, can::ErrorCode::ok);
  client.set(x_gamma_param(), 0.5);
  EXPECT_EQ(client.command(can::CommandCode::save_params).result, can::ErrorCode::ok);
  return storage;
}

TEST(ParamFallback, ADamagedCurrentImageStartsTheNodeWithThePreviousSetAndReportsIt) {
  const std::string storage = two_saves("tnv_fallback_");
  damage(storage, 30);
  auto bus = make_fallback_bus(storage);
  EXPECT_NE(bus->startup_note().find("previous saved set"), std::string::npos) << bus->startup_note();
  EXPECT_NE(bus->startup_note().find("storage_corrupt"), std::string::npos) << bus->startup_note();
  NodeClient client(*bus, 1);
  EXPECT_EQ(client.get(x_gamma_param()), 0.25) << "the previous saved gamma, whole";
  EXPECT_TRUE(bus->node().storage_fault());
  const can_host::Heartbeat hb = client.wait_heartbeat(Micros{300'000});
  EXPECT_NE(hb.errors & can::kHbStorageFault, 0) << "storage_fault not in HEARTBEAT.errors";

  // load_params over CAN falls back the same way, and reports it the same way.
  client.set(x_gamma_param(), 0.125);
  EXPECT_EQ(client.command(can::CommandCode::load_params).result, can::ErrorCode::ok);
  EXPECT_EQ(client.get(x_gamma_param()), 0.25);
  EXPECT_TRUE(bus->node().storage_fault());

  // A save clears it: the new image is current, the damaged one becomes the previous.
  EXPECT_EQ(client.command(can::CommandCode::save_params).result, can::ErrorCode::ok);
  EXPECT_FALSE(bus->node().storage_fault());
  std::filesystem::remove(storage);
  std::filesystem::remove(storage + ".prev");
}

// Swapped generations: the current file is the older save. The node starts
// with the newer set and reports the rollback instead of loading it silently.
TEST(ParamFallback, SwappedGenerationsStartTheNodeWithTheNewerSetAndReportIt) {
  const std::string storage = two_saves("tnv_rollback_");
  // current = generation 2 (0.5), .prev = generation 1 (0.25): swap them.
  const std::string aside = storage + ".swap";
  std::filesystem::rename(storage, aside);
  std::filesystem::rename(storage + ".prev", storage);
  std::filesystem::rename(aside, storage + ".prev");
  auto bus = make_fallback_bus(storage);
  EXPECT_NE(bus->startup_note().find("generation 1 is older than the previous file's 2"), std::string::npos)
      << bus->startup_note();
  NodeClient client(*bus, 1);
  EXPECT_EQ(client.get(x_gamma_param()), 0.5) << "the newer saved gamma";
  EXPECT_TRUE(bus->node().storage_fault());
  std::filesystem::remove(storage);
  std::filesystem::remove(storage + ".prev");
}

}  // namespace
}  // namespace tnv
