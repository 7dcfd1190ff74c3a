// tnv-protogen: writes the DBC and the protocol document from the protocol table.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "firmware/can/can_id.hpp"
#include "tools/cli/cli_frame.hpp"
#include "tools/protogen/dbc_writer.hpp"
#include "tools/protogen/protocol_doc_writer.hpp"

namespace {

bool write_file(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f << text;
  f.close();
  if (!f) {
    std::cerr << "tnv-protogen: cannot write " << path << '\n';
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Writes docs/tnv.dbc and docs/can-protocol.md from the protocol table in firmware/can/."};
  std::string dbc_path;
  std::string doc_path;
  int node = 1;
  app.add_option("--dbc", dbc_path, "write the DBC here ('-' = stdout)");
  app.add_option("--doc", doc_path, "write the Markdown protocol document here ('-' = stdout)");
  app.add_option("--node", node, "node id the DBC's identifiers are for")->check(CLI::Range(1, int{tnv::fw::can::kMaxNodeId}));
  tnv::cli::add_version_flag(app, "tnv-protogen");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return tnv::cli::report_parse_error(app, e, "tnv-protogen", 2);
  }
  if (dbc_path.empty() && doc_path.empty()) {
    std::cerr << "tnv-protogen: nothing to do: give --dbc and/or --doc\n";
    return 2;
  }
  bool ok = true;
  const auto emit = [&](const std::string& path, const std::string& text) {
    if (path.empty()) return;
    if (path == "-") std::cout << text;
    else ok = write_file(path, text) && ok;
  };
  emit(dbc_path, tnv::protogen::write_dbc(static_cast<std::uint8_t>(node)));
  emit(doc_path, tnv::protogen::write_protocol_doc());
  return ok ? 0 : 1;
}
