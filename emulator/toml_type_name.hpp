#pragma once
// "expected a number, got a string": the article and name of a TOML node's
// type, for the one-line errors of every TOML reader (scenario files here,
// the tnv-fw daemon's config).
#include <toml++/toml.h>

namespace tnv::emu {

inline const char* toml_type_name(const toml::node& node) noexcept {
  switch (node.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a float";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    default: return "nothing";
  }
}

}  // namespace tnv::emu
