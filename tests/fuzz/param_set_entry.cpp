// Fuzz entry: PARAM_REQUEST sequences against a model of the staged set.
// Invariants: get reads the live value; an accepted set changes that one
// parameter to exactly the value sent and nothing else; stage changes no
// live value and the node holds exactly the model's staged set; an
// accepted commit applies every staged value exactly and nothing else; a
// refused request (set, stage, commit) changes no live parameter (and a
// refused commit keeps the staged set); discard empties it.
#include <bit>
#include <map>
#include <memory>

#include "tests/firmware/can/node_bench.hpp"
#include "tests/fuzz/fuzz_entries.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace tnv::fuzz {

namespace can = fw::can;

namespace {

constexpr std::size_t kParamRecordBytes = 7;

bool same(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

// Every read_write parameter equal in `a` and `b`, except those in `except`.
bool unchanged_except(const can::NodeSettings& a, const can::NodeSettings& b, const std::map<std::uint16_t, double>& except) {
  for (const can::ParamDef& p : can::param_table()) {
    if (p.access != can::Access::read_write || except.count(p.id) != 0) continue;
    if (!same(p.get(a), p.get(b))) return false;
  }
  return true;
}

}  // namespace

std::string param_set(const std::uint8_t* data, std::size_t size) {
  using test::raw_of;
  using can::MessageId;
  using can::ParamOp;
  auto bench = std::make_unique<test::NodeBench>();
  const auto table = can::param_table();
  std::map<std::uint16_t, double> staged;  // the model
  for (std::size_t r = 0; r + kParamRecordBytes <= size; r += kParamRecordBytes) {
    const std::uint8_t* rec = data + r;
    const std::size_t at = r / kParamRecordBytes;
    const auto op = static_cast<ParamOp>(rec[0] % can::kParamOpCount);
    const std::uint16_t id = (rec[1] & 0x80u) != 0 ? static_cast<std::uint16_t>((rec[1] & 0x7Fu) << 8 | rec[2])
                                                   : table[(rec[1] | (rec[2] & 1u) << 7) % table.size()].id;
    const std::uint32_t raw = static_cast<std::uint32_t>(rec[3] | rec[4] << 8 | rec[5] << 16) |
                              static_cast<std::uint32_t>(rec[6]) << 24;
    const can::NodeSettings before = bench->node->settings();
    const hal::CanFrame reply = bench->reply(test::param_request(test::kNode, op, id, raw));
    if (!test::is(reply, MessageId::param_reply)) return broken("not exactly one PARAM_REPLY", at);
    const can::NodeSettings& now = bench->node->settings();
    const auto result = static_cast<can::ErrorCode>(raw_of(reply, MessageId::param_reply, "result"));
    const bool ok = result == can::ErrorCode::ok;
    const can::ParamDef* p = can::find_param(id);

    switch (op) {
      case ParamOp::get:
        if (ok != (p != nullptr)) return broken("get of a known id refused, or of an unknown one accepted", at);
        if (ok && raw_of(reply, MessageId::param_reply, "value") != can::to_wire(*p, p->get(now)))
          return broken("get does not read the live value", at);
        if (!unchanged_except(before, now, {})) return broken("get changed a parameter", at);
        break;
      case ParamOp::set:
        if (ok) {
          if (!same(p->get(now), can::from_wire(*p, raw))) return broken("set did not apply the value sent", at);
          if (!unchanged_except(before, now, {{id, 0.0}})) return broken("set changed another parameter", at);
        } else if (!unchanged_except(before, now, {})) {
          return broken("a refused set changed a parameter", at);
        }
        break;
      case ParamOp::stage:
        if (!unchanged_except(before, now, {})) return broken("stage changed a live parameter", at);
        if (ok) staged[id] = can::from_wire(*p, raw);
        break;
      case ParamOp::commit:
        if (ok) {
          for (const auto& [sid, value] : staged)
            if (!same(can::find_param(sid)->get(now), value)) return broken("commit did not apply a staged value", at);
          if (!unchanged_except(before, now, staged)) return broken("commit changed an unstaged parameter", at);
          staged.clear();
        } else if (!unchanged_except(before, now, {})) {
          return broken("a refused commit changed a parameter", at);
        }
        break;
      case ParamOp::discard:
        if (!ok) return broken("discard refused", at);
        if (!unchanged_except(before, now, {})) return broken("discard changed a parameter", at);
        staged.clear();
        break;
    }
    if (bench->node->staged_count() != staged.size()) return broken("the node's staged set is not the model's", at);
    if (!can::validate(now).ok) return broken("the live set fails validate()", at);
  }
  return {};
}

}  // namespace tnv::fuzz
