#pragma once
// S1 Table 3 as printed (contour error in um: max / mean / std). These are
// targets to compare against, never values to output as our results.
#include <array>
#include <optional>
#include <string_view>

#include "firmware/control/axis_controller.hpp"
#include "tools/score/contour_stats.hpp"

namespace tnv::hil {

struct PaperTable3Row {
  std::string_view scenario;
  ContourStats pid, dvsc, rdvsc;
  const ContourStats& of(fw::ControllerKind kind) const noexcept {
    return kind == fw::ControllerKind::pid ? pid : kind == fw::ControllerKind::dvsc ? dvsc : rdvsc;
  }
};

inline constexpr std::array<PaperTable3Row, 4> kPaperTable3{{
    {"no-cut", {2.8215, 0.2121, 0.2797, 0}, {2.4641, 0.1780, 0.2344, 0}, {1.6720, 0.1786, 0.1772, 0}},
    {"cut-900", {2.6666, 0.5008, 0.4208, 0}, {2.6909, 0.3578, 0.3432, 0}, {1.8671, 0.2719, 0.2273, 0}},
    {"cut-1200", {2.5532, 0.4021, 0.3525, 0}, {2.5376, 0.3535, 0.3424, 0}, {1.9385, 0.2673, 0.2289, 0}},
    {"cut-1500", {2.7733, 0.3573, 0.3398, 0}, {2.6448, 0.3497, 0.3413, 0}, {1.8782, 0.2655, 0.2349, 0}},
}};

inline std::optional<PaperTable3Row> paper_row(std::string_view scenario) noexcept {
  for (const auto& row : kPaperTable3)
    if (row.scenario == scenario) return row;
  return std::nullopt;
}

}  // namespace tnv::hil
