#include "tools/can/param_file.hpp"

#include <algorithm>
#include <cstdio>
#include <set>
#include <string_view>
#include <toml++/toml.h>

#include "firmware/can/can_id.hpp"
#include "tools/can/param_text.hpp"

namespace tnv::can_host {

namespace {

// A key or message quoted from the file into a one-line error.
std::string one_line(std::string_view text) {
  std::string out(text);
  std::ranges::replace(out, '\n', ' ');
  std::ranges::replace(out, '\r', ' ');
  return out;
}

std::string line_of(const toml::node& n) {
  return "line " + std::to_string(n.source().begin.line) + ": ";
}

// The value as the text parse_param_value() reads; nullopt for arrays, tables, dates.
std::optional<std::string> value_text(const toml::node& n) {
  if (const auto* s = n.as_string()) return s->get();
  if (const auto* i = n.as_integer()) return std::to_string(i->get());
  if (const auto* f = n.as_floating_point()) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", f->get());
    return std::string(buf);
  }
  if (const auto* b = n.as_boolean()) return std::string(b->get() ? "on" : "off");
  return std::nullopt;
}

// [params] holds dotted keys (x.sliding.gamma = 0.25), which TOML nests:
// walk the tables and rebuild each full name.
bool read_params(const toml::table& table, const std::string& prefix, ParamFile& file, std::set<std::uint16_t>& seen,
                 std::string& error) {
  for (const auto& [key, node] : table) {
    const std::string name = prefix + std::string(key.str());
    if (const toml::table* inner = node.as_table()) {
      if (!read_params(*inner, name + ".", file, seen, error)) return false;
      continue;
    }
    const can::ParamDef* p = can::find_param(name.c_str());
    if (p == nullptr) {
      error = line_of(node) + "params." + name + ": no such parameter";
      if (const std::string close = closest_param_name(name); !close.empty()) error += " (did you mean " + close + "?)";
      return false;
    }
    if (p->access != can::Access::read_write) {
      error = line_of(node) + "params." + name + ": read-only, not part of a parameter set";
      return false;
    }
    if (!seen.insert(p->id).second) {
      error = line_of(node) + "params." + name + ": given twice";
      return false;
    }
    const std::optional<std::string> text = value_text(node);
    if (!text) {
      error = line_of(node) + "params." + name + ": expected a number, a name or a boolean";
      return false;
    }
    std::string why;
    const std::optional<double> v = parse_param_value(*p, *text, why);
    if (!v) {
      error = line_of(node) + why;
      return false;
    }
    file.params.push_back({p, *v});
  }
  return true;
}

std::uint32_t hex_u32(const std::string& text, bool& ok) {
  if (text == "unknown") return 0;
  char* end = nullptr;
  const unsigned long v = std::strtoul(text.c_str(), &end, 16);
  ok = !text.empty() && text.size() <= 8 && end == text.c_str() + text.size();
  return static_cast<std::uint32_t>(v);
}

std::uint32_t version_number(const std::string& text, bool& ok) {
  unsigned major = 0, minor = 0, patch = 0;
  int used = 0;
  ok = std::sscanf(text.c_str(), "%u.%u.%u%n", &major, &minor, &patch, &used) == 3 &&
       static_cast<std::size_t>(used) == text.size() && minor < 100 && patch < 100 && major < 100000;
  return major * 10000 + minor * 100 + patch;
}

}  // namespace

std::string params_hash(const std::vector<ParamValue>& params) {
  std::uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a 64 offset basis
  auto mix = [&h](const std::string& s) {
    for (const char c : s) {
      h ^= static_cast<unsigned char>(c);
      h *= 0x100000001b3ull;  // FNV-1a 64 prime
    }
  };
  // Each value as the node holds it (through its wire form: float32 or integer), so text that reads
  // as the same value hashes the same.
  for (const ParamValue& v : params) {
    const double held = can::from_wire(*v.param, can::to_wire(*v.param, v.value));
    mix(std::string(v.param->name) + "=" + format_param_value(*v.param, held) + "\n");
  }
  char buf[40];
  std::snprintf(buf, sizeof buf, "fnv1a64:%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::string write_param_file(std::uint32_t node_id, const NodeIdentity& identity, const std::string& exported_utc,
                             const std::vector<ParamValue>& params, const std::string& origin) {
  std::string out = "# A TNV-40 node's parameter set (" + origin + "). `tnvctl params import`\n"
                    "# applies it as one set; an edited file needs --edited (params_hash).\n\n[node]\n";
  out += "id = " + std::to_string(node_id) + "\n";
  out += "firmware_version = \"" + firmware_version_text(identity.firmware_version) + "\"\n";
  out += "build_id = \"" + build_id_text(identity.build_id) + "\"\n";
  out += "protocol_version = " + std::to_string(identity.protocol_version) + "\n";
  out += "exported_utc = \"" + exported_utc + "\"\n";
  out += "params_hash = \"" + params_hash(params) + "\"\n\n[params]\n";
  for (const ParamValue& v : params) {
    const std::string text = format_param_value(*v.param, v.value);
    const bool named = v.param->values[0] != '\0' && text.find_first_not_of("0123456789.-+e") != std::string::npos;
    out.append(v.param->name).append(" = ");
    out += named ? "\"" + text + "\"" : text;
    out.append("   # ").append(v.param->unit[0] != '\0' ? v.param->unit : "-").append("\n");
  }
  return out;
}

std::optional<ParamFile> read_param_file(const std::string& text, std::string& error) {
  toml::table root;
  try {
    root = toml::parse(text);
  } catch (const toml::parse_error& e) {
    error = "line " + std::to_string(e.source().begin.line) + ": not TOML: " + one_line(e.description());
    return std::nullopt;
  }
  const toml::table* node = root["node"].as_table();
  const toml::table* params = root["params"].as_table();
  if (node == nullptr || params == nullptr) {
    error = "not a parameter file: it needs a [node] and a [params] table (tnvctl params export writes one)";
    return std::nullopt;
  }
  for (const auto& [key, value] : root) {
    if (key.str() != "node" && key.str() != "params") {
      error = line_of(value) + one_line(key.str()) + ": unknown table (a file has [node] and [params])";
      return std::nullopt;
    }
  }
  ParamFile file;
  const auto id = (*node)["id"].value<std::int64_t>();
  const auto firmware = (*node)["firmware_version"].value<std::string>();
  const auto build = (*node)["build_id"].value<std::string>();
  const auto protocol = (*node)["protocol_version"].value<std::int64_t>();
  const auto hash = (*node)["params_hash"].value<std::string>();
  if (!id || *id < 0 || *id > tnv::fw::can::kMaxNodeId || !firmware || !build || !protocol || *protocol < 0 || !hash) {
    error = line_of(*node) +
            "[node] needs id (1..31, 0 for a set not read from a node), firmware_version, build_id, protocol_version and params_hash as an export "
            "writes them";
    return std::nullopt;
  }
  bool version_ok = false, build_ok = false;
  file.node_id = static_cast<std::uint32_t>(*id);
  file.identity.firmware_version = version_number(*firmware, version_ok);
  file.identity.build_id = hex_u32(*build, build_ok);
  file.identity.protocol_version = static_cast<std::uint32_t>(*protocol);
  if (!version_ok || !(build_ok || *build == "unknown")) {
    error = line_of(*node) + "[node] firmware_version is MAJOR.MINOR.PATCH and build_id 8 hex digits or \"unknown\"";
    return std::nullopt;
  }
  file.exported_utc = (*node)["exported_utc"].value_or(std::string());
  file.params_hash = *hash;
  std::set<std::uint16_t> seen;
  if (!read_params(*params, "", file, seen, error)) {
    error = one_line(error);
    return std::nullopt;
  }
  if (file.params.empty()) {
    error = "[params] is empty: nothing to import";
    return std::nullopt;
  }
  // TOML tables have no order: put the values back in table (id) order, the export's.
  std::sort(file.params.begin(), file.params.end(),
            [](const ParamValue& a, const ParamValue& b) { return a.param->id < b.param->id; });
  file.hash_matches = params_hash(file.params) == file.params_hash;
  return file;
}

}  // namespace tnv::can_host
