// NodeClient: BORE_GAUGE, answered by BORE_INFEED (boring on the board, S4).
#include <cstdio>

#include "tools/can/node_client.hpp"

namespace tnv::can_host {

BoreInfeed NodeClient::bore(can::BoreOp op, std::uint16_t part, std::optional<double> top_mm,
                            std::optional<double> bottom_mm) {
  std::string what = std::string("bore ") + can::to_string(op);
  if (op == can::BoreOp::record) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " of part %u", static_cast<unsigned>(part));
    what += buf;
  }
  if (op != can::BoreOp::query) need_ownership();  // record and restart change the planner
  const std::uint8_t tag = next_tag();
  const hal::CanFrame f = transact(bore_gauge_request(node_, tag, op, part, top_mm, bottom_mm), tag,
                                   can::MessageId::bore_infeed, [](const hal::CanFrame&, can::MessageId) { return true; },
                                   what);
  const BoreInfeed r = read_bore_infeed(f);
  if (r.result == can::ErrorCode::not_owner) owned_ = false;
  if (r.result != can::ErrorCode::ok) {
    std::string message = "node ";
    message.append(std::to_string(node_)).append(" refused '").append(what).append("': ").append(can::to_string(r.result));
    if (r.detail != 0) message.append(" (field ").append(bore_gauge_field_name(r.detail)).append(")");
    if (r.result == can::ErrorCode::not_ready) message += ": the planner is off (bore.enable)";
    if (r.result == can::ErrorCode::out_of_range && bore_gauge_field_name(r.detail) == "part")
      message += ": not the next part (params get bore.parts)";
    throw RequestError(RequestError::Kind::refused, message, r.result);
  }
  return r;
}

}  // namespace tnv::can_host
