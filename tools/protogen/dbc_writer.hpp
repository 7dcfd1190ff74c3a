#pragma once
// docs/tnv.dbc from the protocol table: one BO_ per message for one node
// (identifiers carry the node id), signals with scaling, units, value
// tables and float types, comments from the table's doc strings.
#include <cstdint>
#include <string>

namespace tnv::protogen {

std::string write_dbc(std::uint8_t node = 1);

}  // namespace tnv::protogen
