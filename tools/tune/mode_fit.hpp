#pragma once
// Structural-mode identification from the tool-side accelerometer (the
// mode fit: "a structural mode if present"). The excitation steps give the table two
// strong acceleration pulses each (the step's start and end); the tool
// point follows the table through the mode, so after each pulse it reads
//
//   a_tool(t) = c1 e^{-t/tau} + c0 + e^{-zeta w t} (A cos w_d t + B sin w_d t),
//   w_d = w sqrt(1 - zeta^2)
//
// (the forced part: the table's own first-order transient, tau identified
// from the encoder; the free part: the mode ringing). One (f, zeta) is
// fitted to all windows at once, each window with its own linear
// coefficients (variable projection: c1, c0, A, B by least squares for each
// (f, zeta); (f, zeta) by a coarse grid and five zooms).
//
// "No mode" when the damped sinusoid does not explain the residual:
// found only if it removes at least kMinExplainedShare of what the
// table-only model (c1 e^{-t/tau} + c0) leaves, and its largest ring
// amplitude is at least kMinRingLsb accelerometer LSB; and the frequency is
// inside the searched band (not on its edge).
#include <cstddef>
#include <string>
#include <vector>

namespace tnv::tune {

inline constexpr double kModeSearchMinHz = 3.0;
inline constexpr double kModeSearchMaxHz = 400.0;  // 0.8 x the 500 Hz Nyquist frequency of the 1 ms tick
inline constexpr double kModeSearchMinZeta = 1e-3;
inline constexpr double kModeSearchMaxZeta = 0.3;
inline constexpr double kMinExplainedShare = 0.5;
inline constexpr double kMinRingLsb = 10.0;

// One stretch of accelerometer samples after an acceleration pulse.
struct AccelWindow {
  std::vector<double> accel_mm_s2;  // at t = j period, j = 0..n-1, from the window start
  double table_tau_s = 0.0;         // the table transient's time constant in the window (0: none)
};

struct ModeFit {
  bool found = false;
  std::string note;                  // why not found (or empty)
  double freq_hz = 0.0;              // natural frequency f = w / 2 pi
  double zeta = 0.0;
  double ring_amplitude_mm_s2 = 0.0; // largest sqrt(A^2 + B^2) over the windows
  double explained_share = 0.0;      // 1 - SSE(with mode) / SSE(table only)
  double residual_rms_mm_s2 = 0.0;   // what the full model leaves
  int samples = 0;
};

// lsb_mm_s2: the accelerometer's resolution (the ring threshold); samples
// within 1.5 LSB of the 12-bit ADC's end codes are taken as saturated and left out.
ModeFit fit_mode(const std::vector<AccelWindow>& windows, double period_s, double lsb_mm_s2);

// The two windows of one excitation step: `accel_mm_s2` at the ticks j = 0..
// from the step start (sample j taken j periods after the command changed),
// `drive_ticks` ticks of drive then the settle. The start window runs from
// j = 1 to the end of the drive; the end window starts once the table has
// stopped (Coulomb: t = tau ln((|V| + f_c) / f_c), V the step's steady
// speed), plus one tick, to the end of the record.
std::vector<AccelWindow> step_accel_windows(const std::vector<double>& accel_mm_s2, std::size_t drive_ticks,
                                            double tau_s, double speed_mm_s, double coulomb_mm_s, double period_s);

}  // namespace tnv::tune
