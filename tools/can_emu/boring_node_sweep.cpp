#include "tools/can_emu/boring_node_sweep.hpp"

#include <unistd.h>

#include <filesystem>
#include <memory>

#include "tools/can/boring_node_link.hpp"
#include "tools/can_emu/emulated_bus.hpp"

namespace tnv::can_host {

hil::BoringSweepResult run_boring_sweep_on_emulated_node(const hil::BoringRunRequest& request, int seeds,
                                                         const hil::BoringProgress& progress, std::string& error) {
  EmulatedNodeOptions options;
  std::string file = "tnv_hil_boring_";
  file.append(std::to_string(::getpid()));
  options.storage_path = (std::filesystem::temp_directory_path() / file).string();  // read at start, never written
  std::unique_ptr<EmulatedBus> bus = EmulatedBus::create(options, error);
  if (!bus) return {};
  NodeClient client(*bus, bus->node_id());
  BoringNodeLink planner(client);
  return hil::run_boring_sweep(request, seeds, planner, progress);
}

}  // namespace tnv::can_host
