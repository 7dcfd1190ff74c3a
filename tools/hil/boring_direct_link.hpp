#pragma once
// The S4 planner called in this process: the firmware's BoringInfeedPlanner
// kept as one object over the parts, as run_boring() used it before the
// planner moved onto the node. At the node's resolution (the default) its
// settings, readings and infeeds are what the node's would be
// (boring_node_resolution.hpp), so it gives the node's infeeds bit for bit;
// `exact` skips that (doubles throughout: the analytic checks). It also
// runs what the node does not carry (decimal logs, start-up in the RLS,
// more than two positions).
#include <optional>

#include "firmware/adaptive/boring/boring_infeed_planner.hpp"
#include "tools/score/boring_planner_link.hpp"

namespace tnv::hil {

class BoringDirectLink final : public BoringPlannerLink {
 public:
  explicit BoringDirectLink(bool node_resolution = true) : node_resolution_(node_resolution) {}
  std::string start(const fw::BoringPlannerParams& params, const std::vector<double>& positions_mm) override;
  std::vector<BoringLinkInfeed> infeeds(std::string& error) override;
  BoringLinkPart record(int part, const std::vector<double>& bore_error_mm) override;
  double received_reading_mm(double bore_error_mm) const override;
  std::string describe() const override;
  // The planner itself (after start()): what it has learned, to compare.
  const fw::BoringInfeedPlanner* planner() const noexcept { return planner_ ? &*planner_ : nullptr; }

 private:
  bool node_resolution_;
  std::optional<fw::BoringInfeedPlanner> planner_;
  std::vector<double> positions_mm_;
  std::vector<double> infeeds_mm_rev_;  // told for the part being cut
};

}  // namespace tnv::hil
