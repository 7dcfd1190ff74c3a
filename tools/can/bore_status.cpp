#include "tools/can/bore_status.hpp"

#include <cstdio>

#include "firmware/can/param_table.hpp"

namespace tnv::can_host {

namespace {

double get(NodeClient& client, const char* name) { return client.get(*can::find_param(name)); }

// What the node holds after the request: counts, estimates and where the infeeds apply.
BoreStatus with_state(NodeClient& client, can::BoreOp op, const BoreInfeed& answer) {
  BoreStatus s;
  s.op = op;
  s.answer = answer;
  s.top_overhang_mm = get(client, "bore.l1_mm");
  s.bottom_overhang_mm = get(client, "bore.l2_mm");
  s.parts = static_cast<std::uint32_t>(get(client, "bore.parts"));
  s.resets = static_cast<std::uint32_t>(get(client, "bore.resets"));
  s.c_hat_mm = get(client, "bore.c_hat_mm");
  s.alpha_hat = get(client, "bore.alpha_hat");
  s.beta_hat = get(client, "bore.beta_hat");
  return s;
}

const char* yes_no(bool on) { return on ? "yes" : "no"; }

}  // namespace

BoreStatus bore_record(NodeClient& client, std::optional<int> part, std::optional<double> top_mm,
                       std::optional<double> bottom_mm) {
  const int number = part ? *part : static_cast<int>(get(client, "bore.parts")) + 1;
  const BoreInfeed answer = client.bore(can::BoreOp::record, static_cast<std::uint16_t>(number & 0xFFFF), top_mm, bottom_mm);
  BoreStatus s = with_state(client, can::BoreOp::record, answer);
  s.part = number;
  return s;
}

BoreStatus bore_query(NodeClient& client) {
  return with_state(client, can::BoreOp::query, client.bore(can::BoreOp::query));
}

BoreStatus bore_restart(NodeClient& client) {
  return with_state(client, can::BoreOp::restart, client.bore(can::BoreOp::restart));
}

std::string bore_status_text(const BoreStatus& s) {
  const BoreInfeed& a = s.answer;
  std::string out;
  char buf[200];
  if (s.op == can::BoreOp::record) {
    std::snprintf(buf, sizeof buf, "part %d recorded%s: out of band top %s, bottom %s%s\n", s.part,
                  a.has(can::kBoreStartup) ? " (start-up part, eq. (10))" : "", yes_no(a.has(can::kBoreTopOut)),
                  yes_no(a.has(can::kBoreBottomOut)),
                  a.has(can::kBoreReset) ? "; variance perturbation: P reset (process change assumed)" : "");
    out += buf;
  } else if (s.op == can::BoreOp::restart) {
    out += "planner restarted: the next part is the start-up part\n";
  }
  const char* which = s.op == can::BoreOp::record ? "next part" : "part to cut now";
  std::snprintf(buf, sizeof buf, "infeed for the %s: %.5f mm/rev at L1 = %g mm%s, %.5f mm/rev at L2 = %g mm%s%s\n", which,
                a.infeed_top_mm_rev, s.top_overhang_mm, a.has(can::kBoreTopLimited) ? " (limited)" : "",
                a.infeed_bottom_mm_rev, s.bottom_overhang_mm, a.has(can::kBoreBottomLimited) ? " (limited)" : "",
                a.has(can::kBoreStarted) ? "" : " (S0: start-up part)");
  out += buf;
  std::snprintf(buf, sizeof buf, "parts recorded %u, resets %u; estimates C %.5g mm, alpha %.4f, beta %.4f%s\n", s.parts,
                s.resets, s.c_hat_mm, s.alpha_hat, s.beta_hat, a.has(can::kBoreAlphaFloor) ? " (alpha floor 0.05 used)" : "");
  out += buf;
  return out;
}

nlohmann::json bore_status_json(const BoreStatus& s) {
  const BoreInfeed& a = s.answer;
  nlohmann::json j = {
      {"op", can::to_string(s.op)},
      {"started", a.has(can::kBoreStarted)},
      {"infeed_mm_rev",
       {{"top", a.infeed_top_mm_rev}, {"bottom", a.infeed_bottom_mm_rev}}},
      {"overhang_mm", {{"top", s.top_overhang_mm}, {"bottom", s.bottom_overhang_mm}}},
      {"infeed_limited", {{"top", a.has(can::kBoreTopLimited)}, {"bottom", a.has(can::kBoreBottomLimited)}}},
      {"alpha_floor", a.has(can::kBoreAlphaFloor)},
      {"parts", s.parts},
      {"resets", s.resets},
      {"estimate", {{"c_mm", s.c_hat_mm}, {"alpha", s.alpha_hat}, {"beta", s.beta_hat}}}};
  if (s.op == can::BoreOp::record) {
    j["part"] = s.part;
    j["startup"] = a.has(can::kBoreStartup);
    j["reset"] = a.has(can::kBoreReset);
    j["out_of_band"] = {{"top", a.has(can::kBoreTopOut)}, {"bottom", a.has(can::kBoreBottomOut)}};
  }
  return j;
}

}  // namespace tnv::can_host
