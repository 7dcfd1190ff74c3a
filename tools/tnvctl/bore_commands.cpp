// tnvctl bore gauge | status | restart: boring on the board (S4). One
// part's gauge readings go to the node's infeed planner, the next part's
// infeeds come back (tools/can/bore_status.hpp).
#include <memory>

#include "tools/can/bore_status.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

struct BoreGaugeOptions {
  std::optional<double> top_mm;
  std::optional<double> bottom_mm;
  std::optional<int> part;
};

void check_reading(const char* name, const std::optional<double>& mm) {
  if (mm && !can_host::bore_reading_fits(*mm))
    throw BadInput(std::string(name) + ": a bore error of -3.2767 .. 3.2767 mm (BORE_GAUGE carries 0.1 um steps)");
}

void check_gauge(const BoreGaugeOptions& o) {
  check_reading("--top-mm", o.top_mm);
  check_reading("--bottom-mm", o.bottom_mm);
}

int report_status(const can_host::BoreStatus& s, Report& report) {
  std::string text = can_host::bore_status_text(s);
  if (!text.empty() && text.back() == '\n') text.pop_back();
  report.line(text);
  report.data["bore"] = can_host::bore_status_json(s);
  return kExitOk;
}

}  // namespace

void add_bore_commands(CLI::App& app, ActionSlot& slot) {
  CLI::App* bore = app.add_subcommand(
      "bore", "boring on the board (S4): a finished part's gauge readings in, the next part's infeeds out");
  bore->require_subcommand(1);

  auto g = std::make_shared<BoreGaugeOptions>();
  CLI::App* gauge = bore->add_subcommand("gauge", "record one part's readings and print the next part's infeeds");
  gauge->add_option("--top-mm", g->top_mm, "diametral bore error at L1 (bore.l1_mm), mm, + = undersize")->required();
  gauge->add_option("--bottom-mm", g->bottom_mm, "diametral bore error at L2 (bore.l2_mm), mm")->required();
  gauge->add_option("--part", g->part,
                    "the part's number since the planner started (default: bore.parts + 1, read from the node); a "
                    "repeated or skipped number is refused")
      ->check(CLI::Range(1, 65535));
  gauge->callback([&slot, g] {
    slot = Action{"bore gauge", true,
                  [g](Session& s, Report& r) {
                    check_gauge(*g);
                    return report_status(can_host::bore_record(s.client(), g->part, g->top_mm, g->bottom_mm), r);
                  },
                  [g] { check_gauge(*g); }};
  });
  bore->add_subcommand("status", "the infeeds of the part to cut now, the parts counted and the estimates")
      ->callback([&slot] {
        slot = Action{"bore status", true,
                      [](Session& s, Report& r) { return report_status(can_host::bore_query(s.client()), r); }};
      });
  bore->add_subcommand("restart", "start learning again: the next part is the start-up part, cut at bore.s0_mm_rev")
      ->callback([&slot] {
        slot = Action{"bore restart", true,
                      [](Session& s, Report& r) { return report_status(can_host::bore_restart(s.client()), r); }};
      });
}

}  // namespace tnv::tnvctl
