#pragma once
// What a node says it runs: its protocol version, firmware version and
// build id (sys.* parameters), read and printed the same way by every tool.
#include <cstdint>
#include <string>

#include "tools/can/node_client.hpp"

namespace tnv::can_host {

struct NodeIdentity {
  std::uint32_t protocol_version = 0;
  std::uint32_t firmware_version = 0;  // major * 10000 + minor * 100 + patch
  std::uint32_t build_id = 0;          // first 32 bits of the commit; 0 = unknown
};

// Three parameter reads. Throws what NodeClient::get throws.
NodeIdentity read_identity(NodeClient& client);

// "0.1.0" for 100.
std::string firmware_version_text(std::uint32_t version);
// "1a2b3c4d", or "unknown" for 0.
std::string build_id_text(std::uint32_t build_id);

}  // namespace tnv::can_host
