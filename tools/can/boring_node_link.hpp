#pragma once
// run_boring()'s planner on a node, over CAN (boring on the board, S4): the
// run's settings go to the bore.* parameters (one staged set, committed
// whole), each part's infeeds come from BORE_INFEED and its readings go out
// in BORE_GAUGE; the estimates and the reset count are read back from the
// read-only parameters. The same on the emulated node and on a real bus.
#include <array>
#include <optional>

#include "tools/can/node_client.hpp"
#include "tools/score/boring_planner_link.hpp"

namespace tnv::can_host {

class BoringNodeLink final : public hil::BoringPlannerLink {
 public:
  explicit BoringNodeLink(NodeClient& client) : client_(client) {}
  std::string start(const fw::BoringPlannerParams& params, const std::vector<double>& positions_mm) override;
  std::vector<hil::BoringLinkInfeed> infeeds(std::string& error) override;
  hil::BoringLinkPart record(int part, const std::vector<double>& bore_error_mm) override;
  double received_reading_mm(double bore_error_mm) const override;
  std::string describe() const override;

 private:
  NodeClient& client_;
  // The answer that told the infeeds of the part being cut (record's carries the limit flags).
  std::optional<BoreInfeed> told_;
  int resets_ = 0;
};

}  // namespace tnv::can_host
