// tnvctl shaper: design one axis' input shaper and switch it on or off.
#include <cstdio>
#include <memory>

#include "firmware/can/param_table.hpp"
#include "hal/axis_choice.hpp"
#include "tools/can/param_text.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

namespace can = fw::can;

struct ShaperOptions {
  std::string axis;
  std::string type = "zvd";
  std::optional<double> freq_hz;
  double zeta = 0.0;
  bool enable = false;
  bool disable = false;
};

double checked(const std::string& axis, const char* suffix, double value) {
  const can::ParamDef& p = param_named(axis + suffix);
  std::string error;
  char text[48];
  std::snprintf(text, sizeof text, "%.9g", value);
  if (!can_host::parse_param_value(p, text, error)) throw BadInput(error);
  return value;
}

// Checks the request; returns the shaper type's number.
double check_shaper(const ShaperOptions& o) {
  parse_axis(o.axis);
  if (!o.freq_hz && !o.enable && !o.disable) throw BadInput("nothing to do: give --freq-hz (a design) and/or --enable/--disable");
  const can::ParamDef& type_param = param_named(o.axis + ".shaper.type");
  std::string error;
  const std::optional<double> type = can_host::parse_param_value(type_param, o.type, error);
  if (!type) throw BadInput(error);
  if (o.freq_hz) {
    checked(o.axis, ".shaper.freq_hz", *o.freq_hz);
    checked(o.axis, ".shaper.zeta", o.zeta);
  }
  return *type;
}

int run_shaper(const ShaperOptions& o, Session& session, Report& report) {
  const std::uint8_t axis = parse_axis(o.axis);
  const double type = check_shaper(o);
  can_host::NodeClient& client = session.client();
  if (o.freq_hz) {
    client.shaper(axis, static_cast<std::uint8_t>(type), *o.freq_hz, o.zeta);
    char buf[160];
    std::snprintf(buf, sizeof buf, "shaper %s: %s at %g Hz, zeta %g (applies at the next quiet reference)",
                  o.axis.c_str(), o.type.c_str(), *o.freq_hz, o.zeta);
    report.line(buf);
    report.data["design"] = {{"type", o.type}, {"freq_hz", *o.freq_hz}, {"zeta", o.zeta}};
  }
  if (o.enable || o.disable) {
    client.command(can::CommandCode::shaper_enable, axis, o.enable ? 1 : 0);
    std::string text = "shaper ";
    report.line(text.append(o.axis).append(o.enable ? ": on" : ": off"));
    report.data["enabled"] = o.enable;
  }
  return kExitOk;
}

}  // namespace

void add_shaper_commands(CLI::App& app, ActionSlot& slot) {
  auto o = std::make_shared<ShaperOptions>();
  CLI::App* cmd = app.add_subcommand("shaper", "design one axis' input shaper and/or switch it on or off");
  cmd->add_option("--axis", o->axis, hal::kAxisChoices)->required()
      ->check(CLI::IsMember(std::vector<std::string>(hal::kAxisNames.begin(), hal::kAxisNames.end())));
  cmd->add_option("--type", o->type, "zv | zvd | zvdd | ei | mzv")
      ->check(CLI::IsMember({"zv", "zvd", "zvdd", "ei", "mzv"}))
      ->capture_default_str();
  cmd->add_option("--freq-hz", o->freq_hz, "mode frequency to cancel, Hz");
  cmd->add_option("--zeta", o->zeta, "mode damping ratio")->capture_default_str();
  auto* on = cmd->add_flag("--enable", o->enable, "switch the shaper on");
  auto* off = cmd->add_flag("--disable", o->disable, "switch the shaper off");
  on->excludes(off);
  cmd->callback([&slot, o] {
    slot = Action{"shaper", true, [o](Session& s, Report& r) { return run_shaper(*o, s, r); },
                  [o] { check_shaper(*o); }};
  });
}

}  // namespace tnv::tnvctl
