#pragma once
// The test-and-learning stage before the cut (S3 section 3, Fig. 5): the
// process is driven open loop with a known input at constant depth and
// the model is fitted by batch least squares. For the robust variant
// only the structured model (feed drive and force pole, plus the cutting
// gain at that depth) is fitted; it never looks at the process parameters.
#include <cstdint>
#include <vector>

#include "emulator/milling_process.hpp"
#include "firmware/adaptive/arsc/robust_gain_solve.hpp"

namespace tnv::hil {

struct TestStageSample {
  double force = 0.0;  // y(t)
  double feed = 0.0;
  double u = 0.0;      // applied over [t, t+1)
};

struct TestStageFit {
  fw::arsc::StructuredModel model{};
  double drive_bias = 0.0;     // constant term of the drive fit (friction offset), not used by the design
  double drive_rms = 0.0;      // residual rms of the drive equation
  double force_rms = 0.0;      // residual rms of the force equation
  std::size_t samples = 0;
};

// Batch least squares of
//   v(t) = -a11 v(t-1) + b11 u(t-1) - c11 f(t-1) [+ bias]     S3 eq. (27)
//   f(t) = -a21 f(t-1) + g v(t-1)                              S3 eq. (28)
TestStageFit fit_structured_model(const std::vector<TestStageSample>& samples, bool with_bias);

// A deterministic pseudo-random two-level input u0 +- amplitude, switching
// with probability 1/2 every `hold` samples (a PRBS-like excitation).
std::vector<double> test_stage_input(std::size_t count, double u0, double amplitude, std::size_t hold,
                                     std::uint32_t seed);

// The paper's process at constant depth driven by test_stage_input.
std::vector<TestStageSample> run_test_stage(const emu::MillingProcessParams& process, double depth_mm,
                                            std::size_t count);

}  // namespace tnv::hil
