// tnvctl params export | import: a node's parameter set as a TOML file
// (tools/can/param_file.hpp), applied back as one all-or-nothing set.
#include <cstdio>
#include <filesystem>
#include <ctime>
#include <iostream>
#include <memory>

#include "drivers/storage/regular_file.hpp"
#include "tools/can/node_identity.hpp"
#include "tools/can/param_file.hpp"
#include "tools/can/param_text.hpp"
#include "tools/cli/output_path.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

namespace can = fw::can;

constexpr std::size_t kMaxParamFileBytes = 1 << 20;  // an export is about 20 kB

struct ExportOptions {
  std::string path = "-";  // "-" = stdout
};

struct ImportOptions {
  std::string path;
  bool edited = false;    // import a file whose values changed after the export
  bool any_node = false;  // import a file exported from another node id
};

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  ::gmtime_r(&now, &utc);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buf;
}

int run_export(const ExportOptions& o, Session& session, Report& report) {
  can_host::NodeClient& client = session.client();
  const can_host::NodeIdentity identity = can_host::read_identity(client);
  std::vector<can_host::ParamValue> values;
  for (const can::ParamDef& p : can::param_table())
    if (p.access == can::Access::read_write) values.push_back({&p, client.get(p)});
  const std::string text = can_host::write_param_file(client.node(), identity, utc_now(), values);
  if (o.path == "-") {
    if (report.json_mode()) throw BadInput("params export to stdout (-) writes TOML: --json needs an output FILE");
    std::cout << text;
    std::cout.flush();
  } else {
    if (!cli::write_file_replacing(o.path, text)) throw RunFailed("cannot write " + o.path);
    char buf[160];
    std::snprintf(buf, sizeof buf, "%zu parameters of node %u (firmware %s, build %s) written to ", values.size(),
                  unsigned{client.node()}, can_host::firmware_version_text(identity.firmware_version).c_str(),
                  can_host::build_id_text(identity.build_id).c_str());
    report.line(buf + o.path);
  }
  report.data["file"] = o.path;
  report.data["params"] = values.size();
  report.data["params_hash"] = can_host::params_hash(values);
  report.data["firmware"] = firmware_json(identity);
  return kExitOk;
}

// Everything that needs no node: the file readable and well formed, intact
// or --edited. Throws BadInput.
can_host::ParamFile checked_file(const ImportOptions& o) {
  std::string text, error;
  if (!drivers::read_regular_file(o.path, kMaxParamFileBytes, drivers::LinkPolicy::follow, text, error)) {
    throw BadInput(error);
  }
  std::optional<can_host::ParamFile> file = can_host::read_param_file(text, error);
  if (!file) throw BadInput(o.path + ": " + error);
  if (!file->hash_matches && !o.edited)
    throw BadInput(o.path + ": its values changed after the export (params_hash " + file->params_hash +
                   " is not theirs): check the changes, then import with --edited");
  return std::move(*file);
}

int run_import(const ImportOptions& o, Session& session, Report& report) {
  const can_host::ParamFile file = checked_file(o);
  // Node 0: a set made by a tool (tnv-hil screw-fit), for any node.
  if (file.node_id != 0 && file.node_id != static_cast<std::uint32_t>(session.options().node) && !o.any_node)
    throw BadInput(o.path + " was exported from node " + std::to_string(file.node_id) + ", not node " +
                   std::to_string(session.options().node) + ": --any-node imports it anyway");
  can_host::NodeClient& client = session.client();
  const can_host::NodeIdentity identity = can_host::read_identity(client);
  if (identity.protocol_version != file.identity.protocol_version)
    throw RunFailed(o.path + " holds protocol version " + std::to_string(file.identity.protocol_version) +
                    " parameters and the node speaks " + std::to_string(identity.protocol_version) +
                    ": nothing imported");
  if (identity.firmware_version != file.identity.firmware_version || identity.build_id != file.identity.build_id)
    std::fprintf(stderr, "tnvctl: note: %s was exported from firmware %s (build %s); the node runs %s (build %s)\n",
                 o.path.c_str(), can_host::firmware_version_text(file.identity.firmware_version).c_str(),
                 can_host::build_id_text(file.identity.build_id).c_str(),
                 can_host::firmware_version_text(identity.firmware_version).c_str(),
                 can_host::build_id_text(identity.build_id).c_str());
  // Only what differs goes to the node: a safety parameter the file leaves
  // as it is needs no commissioning mode.
  std::vector<std::string> assignments;
  for (const can_host::ParamValue& v : file.params)
    if (can::to_wire(*v.param, client.get(*v.param)) != can::to_wire(*v.param, v.value))
      assignments.push_back(std::string(v.param->name) + "=" + can_host::format_param_value(*v.param, v.value));
  report.data["file"] = o.path;
  report.data["in_file"] = file.params.size();
  if (assignments.empty()) {
    report.line("node " + std::to_string(client.node()) + " already holds the " + std::to_string(file.params.size()) +
                " parameters of " + o.path + ": nothing to change");
    report.data["applied"] = 0;
    report.data["params"] = nlohmann::json::array();
    return kExitOk;
  }
  return set_params(assignments, session, report);
}

}  // namespace

void add_param_file_commands(CLI::App& params, ActionSlot& slot) {
  auto ex = std::make_shared<ExportOptions>();
  CLI::App* export_cmd = params.add_subcommand(
      "export", "write every writable parameter to a TOML file (with node id, firmware version and a hash)");
  export_cmd->add_option("file", ex->path, "FILE, or - for stdout")
      ->capture_default_str()
      ->check([](const std::string& path) { return path == "-" ? std::string() : cli::output_file_problem(path); });
  export_cmd->callback([&slot, ex] {
    slot = Action{"params export", true, [ex](Session& s, Report& r) { return run_export(*ex, s, r); }};
  });

  auto im = std::make_shared<ImportOptions>();
  CLI::App* import_cmd = params.add_subcommand(
      "import", "apply a file from `params export` as one set (all or nothing); only what differs is sent");
  import_cmd->add_option("file", im->path, "FILE written by params export")->required();
  import_cmd->add_flag("--edited", im->edited, "import a file whose values were changed after the export");
  import_cmd->add_flag("--any-node", im->any_node, "import a file exported from another node id");
  import_cmd->callback([&slot, im] {
    slot = Action{"params import", true, [im](Session& s, Report& r) { return run_import(*im, s, r); },
                  // A script may export the file on an earlier line: a file not there yet is checked when its line runs.
                  [im] {
                    if (std::filesystem::exists(im->path)) checked_file(*im);
                  }};
  });
}

}  // namespace tnv::tnvctl
