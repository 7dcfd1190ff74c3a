#include "tools/can/node_identity.hpp"

#include <cstdio>

#include "firmware/can/param_table.hpp"

namespace tnv::can_host {

namespace {

std::uint32_t read_u32(NodeClient& client, const char* name) {
  return static_cast<std::uint32_t>(client.get(*fw::can::find_param(name)));
}

}  // namespace

NodeIdentity read_identity(NodeClient& client) {
  NodeIdentity id;
  id.protocol_version = read_u32(client, "sys.protocol_version");
  id.firmware_version = read_u32(client, "sys.firmware_version");
  id.build_id = read_u32(client, "sys.build_id");
  return id;
}

std::string firmware_version_text(std::uint32_t version) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%u.%u.%u", version / 10000, version / 100 % 100, version % 100);
  return buf;
}

std::string build_id_text(std::uint32_t build_id) {
  if (build_id == 0) return "unknown";
  char buf[16];
  std::snprintf(buf, sizeof buf, "%08x", build_id);
  return buf;
}

}  // namespace tnv::can_host
