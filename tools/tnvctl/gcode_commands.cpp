// tnvctl gcode canon: a program's canonical machine calls as LinuxCNC's
// rs274 prints them (tools/gcode/canon_interpreter.hpp; no device needed).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "tools/cli/gcode_setup_options.hpp"
#include "tools/gcode/canon_interpreter.hpp"
#include "tools/gcode/canon_text_spool.hpp"
#include "tools/gcode/gcode_error.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

struct CanonOptions {
  std::string program;
  cli::GcodeSetupOptions files;
  cli::FromLineOptions from;
  std::vector<double> machine_position;  // X Y Z, or empty
};

gcode::CanonSetup load_setup(const CanonOptions& o) {
  gcode::CanonSetup setup;
  std::string error;
  if (!cli::load_gcode_setup(o.files, setup, error)) throw BadInput(error);
  cli::apply_from_line(o.from, setup);
  if (setup.from_line)
    for (std::size_t a = 0; a < o.machine_position.size() && a < 3; ++a)
      setup.from_line->machine_position_mm[a] = o.machine_position[a];
  return setup;
}

[[noreturn]] void refuse(const CanonOptions& o, const gcode::GcodeError& e) {
  // Nothing printed but the error: a refused program emits no call.
  throw BadInput(e.line == 0 ? e.message : o.program + ": " + gcode::to_string(e));
}

int run_canon(const CanonOptions& o, Session&, Report& report) {
  const gcode::CanonSetup setup = load_setup(o);
  if (report.json_mode()) {  // one JSON object, printed at the end: the calls are held
    const gcode::CanonResult r = gcode::interpret_canon_file(o.program, setup);
    if (r.error) refuse(o, *r.error);
    nlohmann::json calls = nlohmann::json::array();
    for (const gcode::CanonCall& c : r.calls) calls.push_back({{"line", c.line}, {"call", c.text}});
    report.data["calls"] = calls;
    return kExitOk;
  }
  // The calls go to a temporary file as they are made and are printed only
  // once the program has run to its end: memory does not grow with them.
  gcode::CanonTextSpool spool;
  const gcode::CanonRun run =
      gcode::interpret_canon_file_to(o.program, setup, [&spool](const gcode::CanonCall& c) { spool(c); });
  if (run.error) refuse(o, *run.error);
  std::string error;
  if (!spool.copy_to(std::cout, error)) throw RunFailed(error);
  return kExitOk;
}

}  // namespace

void add_gcode_commands(CLI::App& app, ActionSlot& slot) {
  CLI::App* gcode = app.add_subcommand("gcode", "G-code tools (no device needed)");
  gcode->require_subcommand(1);
  auto o = std::make_shared<CanonOptions>();
  CLI::App* canon = gcode->add_subcommand(
      "canon", "print a program's canonical machine calls, one per line, as LinuxCNC's rs274 -g prints them");
  canon->add_option("FILE", o->program, "the program (.ngc)")->required();
  cli::add_gcode_setup_options(*canon, o->files);
  CLI::Option* from_line = cli::add_from_line_options(*canon, o->from);
  canon->add_option("--machine-position", o->machine_position,
                    "with --from-line: where the machine is, X Y Z in machine coordinates, mm (default 0 0 0)")
      ->expected(3)
      ->needs(from_line);
  canon->callback([&slot, o] {
    slot = Action{"gcode canon", false, [o](Session& s, Report& r) { return run_canon(*o, s, r); },
                  [o] { (void)load_setup(*o); }};
  });
}

}  // namespace tnv::tnvctl
