// Fuzz entry: a scenario TOML text. Invariants: the parser returns a
// scenario or a one-line error naming the source, never both; an accepted
// scenario passes validate_scenario() (nothing unchecked gets through); its
// fault timeline has its edges in order and hands each out exactly once;
// the same text parses to the same answer again.
#include <string_view>

#include "emulator/fault_timeline.hpp"
#include "emulator/scenario_file.hpp"
#include "emulator/scenario_validation.hpp"
#include "tests/fuzz/fuzz_entries.hpp"

namespace tnv::fuzz {

std::string scenario_toml(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const emu::ScenarioResult r = emu::parse_scenario_text(text, "fuzz.toml");
  if (r.scenario.has_value() == !r.error.empty()) return "the parser returned both or neither of scenario and error";
  if (!r.scenario) {
    if (r.error.rfind("fuzz.toml", 0) != 0) return "an error that does not name the source: " + r.error;
    if (r.error.find('\n') != std::string::npos) return "an error of more than one line: " + r.error;
    return {};
  }
  if (const std::string why = emu::validate_scenario(*r.scenario); !why.empty())
    return "an accepted scenario fails validation: " + why;

  emu::FaultTimeline timeline(r.scenario->faults);
  const auto edges = timeline.edges();
  for (std::size_t i = 1; i < edges.size(); ++i)
    if (edges[i].substep < edges[i - 1].substep) return "fault edges out of order";
  for (const emu::FaultEdge& e : edges)
    if (e.fault >= r.scenario->faults.size()) return "a fault edge names no fault";
  std::size_t handed = 0;
  for (std::uint64_t at = 0; handed < edges.size();) {
    const std::uint64_t step = timeline.substeps_to_next(at);
    if (step == emu::FaultTimeline::kNever) break;
    at += step;
    const auto due = timeline.take_due(at);
    if (due.empty()) return "substeps_to_next() pointed at no edge";
    handed += due.size();
  }
  if (handed != edges.size()) return "the timeline did not hand out every edge exactly once";

  const emu::ScenarioResult again = emu::parse_scenario_text(text, "fuzz.toml");
  if (!again.scenario || again.scenario->name != r.scenario->name ||
      again.scenario->faults.size() != r.scenario->faults.size())
    return "the same text parsed differently the second time";
  return {};
}

}  // namespace tnv::fuzz
