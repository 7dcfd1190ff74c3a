// tnvctl commissioning enter | leave: the node's commissioning mode, the
// only mode in which its safety parameters change (docs/safety.md
// "Commissioning", docs/tuning-guide.md).
#include <string>

#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

namespace can = fw::can;
using can_host::RequestError;

// The node's refusal, with what to do about it.
std::string enter_refusal(const RequestError& e) {
  std::string message = e.what();
  switch (e.code()) {
    case can::ErrorCode::not_permitted:
      message += ": this node does not permit commissioning (tnv-fw: set [safety] allow_commissioning = true in its "
                 "config and restart it, docs/install-board.md)";
      break;
    case can::ErrorCode::busy: message += ": commissioning starts only with the servo disabled (tnvctl disable)"; break;
    case can::ErrorCode::faulted: message += ": clear the fault first (tnvctl clear-faults)"; break;
    default: break;
  }
  return message;
}

int run_commissioning(bool enter, Session& session, Report& report) {
  can_host::NodeClient& client = session.client();
  const can::CommandCode code = enter ? can::CommandCode::enter_commissioning : can::CommandCode::leave_commissioning;
  can_host::CommandAck ack;
  try {
    ack = client.command(code);
  } catch (const RequestError& e) {
    if (e.kind() != RequestError::Kind::refused) throw;
    throw RequestError(RequestError::Kind::refused, enter_refusal(e), e.code());
  }
  report.line(enter ? "commissioning mode: safety parameters may change until leave, enable, motion or a fault"
                    : "commissioning mode left: safety parameters are locked");
  report.data["commissioning"] = enter;
  report.data["state"] = fw::to_string(ack.state);
  return kExitOk;
}

}  // namespace

void add_commissioning_commands(CLI::App& app, ActionSlot& slot) {
  CLI::App* cmd = app.add_subcommand(
      "commissioning", "commissioning mode: the only mode in which safety parameters (limits, scales) change");
  cmd->require_subcommand(1);
  cmd->add_subcommand("enter", "enter it (servo disabled, no fault; tnv-fw needs [safety] allow_commissioning)")
      ->callback([&slot] {
        slot = Action{"commissioning enter", true, [](Session& s, Report& r) { return run_commissioning(true, s, r); }};
      });
  cmd->add_subcommand("leave", "leave it (also left on enable, motion or a fault)")->callback([&slot] {
    slot = Action{"commissioning leave", true, [](Session& s, Report& r) { return run_commissioning(false, s, r); }};
  });
}

}  // namespace tnv::tnvctl
