// tnv::can_host: the emulated node behind its virtual bus, a parameter set
// over the protocol and read back.
#include <cstdio>
#include <string>

#include "firmware/can/param_table.hpp"
#include "tools/can/node_client.hpp"
#include "tools/can_emu/emulated_bus.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::puts("usage: emulated_node STORAGE_FILE");
    return 2;
  }
  tnv::can_host::EmulatedNodeOptions options;
  options.storage_path = argv[1];
  std::string error;
  auto bus = tnv::can_host::EmulatedBus::create(options, error);
  if (!bus) {
    std::printf("emulated node: %s\n", error.c_str());
    return 1;
  }
  tnv::can_host::NodeClient client(*bus, bus->node_id());
  const auto* gamma = tnv::fw::can::find_param("x.sliding.gamma");
  if (gamma == nullptr) return 1;
  const double read_back = client.set(*gamma, 0.3125);
  std::printf("x.sliding.gamma %.4f\n", read_back);
  return read_back == 0.3125 ? 0 : 1;
}
