#pragma once
// Design verification: what given gains do on a model, before they reach
// a table. Each linearised loop (R-DVSC+DDC, DVSC+DDC as gamma = 0, PID)
// and the speed observer's error dynamics (I - L C) Phi, as poles and
// their spectral radius (firmware/control/loop_analysis.hpp,
// matrix_poles.hpp: the same pole computation the firmware's checks use).
#include <complex>
#include <string>
#include <vector>

#include "firmware/control/axis_model.hpp"
#include "firmware/control/pid_params.hpp"
#include "firmware/control/sliding_mode_params.hpp"
#include "firmware/control/speed_observer.hpp"

namespace tnv::tune {

// One linearised loop on a model: spectral radius and poles; ok = false
// (with why) when the gains do not even pass validate() there.
struct LoopPrediction {
  bool ok = false;
  std::string why;
  double spectral_radius = 0.0;
  std::vector<std::complex<double>> poles;
};

LoopPrediction predict_sliding(const fw::AxisModel& model, const fw::SlidingModeParams& p);
LoopPrediction predict_pid(const fw::AxisModel& model, const fw::PidParams& p);
// Also for gains that are not switched on (designed, observer.enable off);
// ok = false for all-zero gains (no observer: its poles would sit at 1).
LoopPrediction predict_observer(const fw::AxisModel& model, const fw::SpeedObserverParams& p);

}  // namespace tnv::tune
