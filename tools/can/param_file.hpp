#pragma once
// A node's parameter set as a TOML file (`tnvctl params export/import`):
// who it came from (node id, firmware version and build, protocol
// version), when, every writable parameter by name in table order, and a
// hash of those values, so an import can tell an intact export from an
// edited one.
//
//   [node]
//   id = 1
//   firmware_version = "0.1.0"
//   build_id = "1a2b3c4d"
//   protocol_version = 3
//   exported_utc = "2026-11-26T03:40:00Z"
//   params_hash = "fnv1a64:0123456789abcdef"
//
//   [params]
//   x.controller = "rdvsc"
//   x.sliding.gamma = 0.25
//   ...
#include <optional>
#include <string>
#include <vector>

#include "firmware/can/param_table.hpp"
#include "tools/can/node_identity.hpp"

namespace tnv::can_host {

struct ParamValue {
  const can::ParamDef* param = nullptr;
  double value = 0.0;
};

struct ParamFile {
  std::uint32_t node_id = 0;  // 0: not read from a node (made by a tool: tnv-hil screw-fit)
  NodeIdentity identity;  // of the node exported from (firmware_version 0 / build_id 0: unknown)
  std::string exported_utc;
  std::string params_hash;           // as written in the file
  std::vector<ParamValue> params;    // in table (id) order, each once
  bool hash_matches = false;         // params_hash is the hash of `params`
};

// The hash of a set of values: FNV-1a (64 bit) over "name=value\n" per
// parameter, each value as the node holds it (its wire form) printed by
// format_param_value().
std::string params_hash(const std::vector<ParamValue>& params);

// `origin` names what wrote the file, in its first comment line.
std::string write_param_file(std::uint32_t node_id, const NodeIdentity& identity, const std::string& exported_utc,
                             const std::vector<ParamValue>& params,
                             const std::string& origin = "tnvctl params export");

// nullopt with `error` ("line L: why", naming the key) for a file that is
// not TOML, lacks [node] or [params], names an unknown or read-only
// parameter, names one twice, or holds a value of the wrong type or out of
// range. A hash that does not match is not an error here (hash_matches).
std::optional<ParamFile> read_param_file(const std::string& text, std::string& error);

}  // namespace tnv::can_host
