#pragma once
// The process an outer force loop sees on the machine (issue 8 item 5):
// it sets the feed (the program's feed override, planned), the axis makes
// the table follow, the cut turns feed into force. In continuous time,
//   T_f df/dt  = -f + G v            S3 eq. (28) in time, G = K delta (cutting gain)
//   tau_v dv/dt = -v + u(t - theta)  the axis under its own controller, S3 eq. (27)'s role
// with the command u taking effect theta after the sample (one tick: the
// command reaches the motion core at the next tick). The feed does not see
// the force: the axis controller rejects the cutting load, so (27)'s -f
// term is the axis controller's job, not the force loop's.
//
// Sampled at period T with u held over [t + theta, t + 1 + theta), the
// exact discretisation (0 <= theta <= T) is
//   x(t+1) = Phi x(t) + Gamma0 u(t) + Gamma1 u(t-1),   x = [f, v]
// (Gamma1: the part of the period the previous command still applies).
// Everything here is normalised: f by a force scale, v and u by a feed
// scale, so g = G v_scale / f_scale. Phi's f row, Gamma0_f and Gamma1_f are
// proportional to g; the v row does not depend on g.
#include <Eigen/Core>

#include "firmware/control/param_check.hpp"

namespace tnv::fw::arsc {

struct FeedForceModel {
  double force_time_constant_s = 0.2;    // T_f
  double drive_time_constant_s = 0.002;  // tau_v: planner + axis as one lag
  double command_delay_s = 0.001;        // theta: sample to first effect of a new command
  double cutting_gain = 0.2;             // g = G v_scale / f_scale (normalised), > 0
};

// Finite; time constants > 0; delay >= 0; g > 0.
ParamCheck validate(const FeedForceModel& model) noexcept;

struct SampledFeedForce {
  Eigen::Matrix2d phi = Eigen::Matrix2d::Identity();
  Eigen::Vector2d gamma0 = Eigen::Vector2d::Zero();  // this sample's command
  Eigen::Vector2d gamma1 = Eigen::Vector2d::Zero();  // the previous command (still applied for theta)
  double force_pole = 0.0;                           // exp(-T / T_f)
  double drive_pole = 0.0;                           // exp(-T / tau_v)
};

// Exact for the model above. Requires validate(model).ok, period_s > 0 and
// command_delay_s <= period_s (a longer delay needs more delay states).
SampledFeedForce discretise(const FeedForceModel& model, double period_s) noexcept;

}  // namespace tnv::fw::arsc
