#pragma once
// The motions the page starts so the scope has something to show, and the
// fault handling: circle, move, stop, e-stop, clear faults. Each returns
// once the node acknowledged it (the scope shows the rest); the commands
// and the two-step clear are NodeClient's and tools/can/motion_run's.
#include <nlohmann/json.hpp>

#include "tools/can_emu/emulated_bus.hpp"
#include "tools/can/node_client.hpp"

namespace tnv::serve {

struct MotionRequest {
  std::string kind;  // enable | disable (servo on / off) | circle | move | stop | estop
  double radius_mm = 0.0;
  double feed_mm_s = 0.0;
  std::uint8_t axis = 0;
  double distance_mm = 0.0;
  double speed_mm_s = 0.0;
};

// Checks the request body before anything is sent: ApiError(400). A circle
// without radius/feed takes the emulated scenario's (`emulated`), else S1's
// 6 mm at 2 mm/s.
MotionRequest parse_motion_request(const nlohmann::json& body, const can_host::EmulatedBus* emulated);

// Sends it (node thread); a refusal throws ApiError(409) with the node's reason.
nlohmann::json start_motion(can_host::NodeClient& client, const MotionRequest& request);

// COMMAND clear_faults (a board latch takes a second clear); a refusal
// (the cause is still there) throws ApiError(409) naming it.
nlohmann::json clear_faults_for_page(can_host::NodeClient& client);

}  // namespace tnv::serve
