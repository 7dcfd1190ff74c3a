#pragma once
// How run_boring() (tools/hil/boring_run.hpp) reaches the S4 infeed
// planner: the node over CAN (tools/can/boring_node_link.hpp: BORE_GAUGE /
// BORE_INFEED and the bore.* parameters) or the firmware planner called in
// this process (tools/hil/boring_direct_link.hpp). A run asks for the
// infeeds at the measuring positions, cuts the part with them, gauges it
// and records the readings.
#include <cstdint>
#include <string>
#include <vector>

#include "firmware/adaptive/boring/boring_planner_params.hpp"

namespace tnv::hil {

struct BoringLinkInfeed {
  double infeed_mm_rev = 0.0;
  bool infeed_limited = false;  // eq. (3) was clamped to the infeed range
};

// What the planner made of one recorded part.
struct BoringLinkPart {
  std::string error;            // the planner refused the part ("" = recorded)
  bool reset = false;           // the variance perturbation reset P during the part
  int resets_total = 0;         // resets since start()
  int out_of_band = 0;          // measured deflections out of band
  double c_hat_mm = 0.0, alpha_hat = 0.0, beta_hat = 0.0;  // after the part
};

class BoringPlannerLink {
 public:
  virtual ~BoringPlannerLink() = default;
  // A planner that has learned nothing, set up with `params` at the
  // measuring overhangs `positions_mm` (in order); "" or why not.
  virtual std::string start(const fw::BoringPlannerParams& params, const std::vector<double>& positions_mm) = 0;
  // The infeeds to cut the next part with, one per position; an empty
  // vector with `error` set when the planner cannot say.
  virtual std::vector<BoringLinkInfeed> infeeds(std::string& error) = 0;
  // The finished part's readings: diametral bore errors (mm, + = undersize),
  // one per position, as the gauge measured them.
  virtual BoringLinkPart record(int part, const std::vector<double>& bore_error_mm) = 0;
  // The reading as the planner receives it (its resolution): what the run
  // turns into the measured deflection it reports.
  virtual double received_reading_mm(double bore_error_mm) const = 0;
  // "node over CAN", "direct": for the report.
  virtual std::string describe() const = 0;
};

}  // namespace tnv::hil
