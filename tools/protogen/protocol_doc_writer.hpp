#pragma once
// docs/can-protocol.md from the protocol table: framing, every message
// and field, result and command codes, heartbeat bits, every parameter
// with its default, capture channels, malformed-frame rules, bus load.
#include <string>

namespace tnv::protogen {

std::string write_protocol_doc();

}  // namespace tnv::protogen
