#include "tools/hil/arsc_test_stage.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "tools/tune/least_squares.hpp"

namespace tnv::hil {

TestStageFit fit_structured_model(const std::vector<TestStageSample>& s, bool with_bias) {
  TestStageFit fit;
  if (s.size() < 8) return fit;
  const auto n = static_cast<Eigen::Index>(s.size() - 1);
  const Eigen::Index drive_cols = with_bias ? 4 : 3;
  Eigen::MatrixXd drive(n, drive_cols), force(n, 2);
  Eigen::VectorXd v_next(n), f_next(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const TestStageSample& a = s[static_cast<std::size_t>(i)];
    const TestStageSample& b = s[static_cast<std::size_t>(i) + 1];
    drive(i, 0) = a.feed;
    drive(i, 1) = a.u;
    drive(i, 2) = a.force;
    if (with_bias) drive(i, 3) = 1.0;
    v_next(i) = b.feed;
    force(i, 0) = a.force;
    force(i, 1) = a.feed;
    f_next(i) = b.force;
  }
  const Eigen::VectorXd pd = tune::least_squares(drive, v_next).x;
  const Eigen::VectorXd pf = tune::least_squares(force, f_next).x;
  fit.model.drive.a11 = -pd(0);
  fit.model.drive.b11 = pd(1);
  fit.model.drive.c11 = -pd(2);
  fit.drive_bias = with_bias ? pd(3) : 0.0;
  fit.model.a21 = -pf(0);
  fit.model.cutting_gain = pf(1);
  fit.drive_rms = std::sqrt((drive * pd - v_next).squaredNorm() / static_cast<double>(n));
  fit.force_rms = std::sqrt((force * pf - f_next).squaredNorm() / static_cast<double>(n));
  fit.samples = s.size();
  return fit;
}

std::vector<double> test_stage_input(std::size_t count, double u0, double amplitude, std::size_t hold,
                                     std::uint32_t seed) {
  std::vector<double> u(count);
  std::uint32_t state = seed == 0 ? 0x9E3779B9u : seed;
  double level = u0 + amplitude;
  for (std::size_t i = 0; i < count; ++i) {
    if (hold > 0 && i % hold == 0) {
      state ^= state << 13;  // xorshift32
      state ^= state >> 17;
      state ^= state << 5;
      level = (state & 1u) ? u0 + amplitude : u0 - amplitude;
    }
    u[i] = level;
  }
  return u;
}

std::vector<TestStageSample> run_test_stage(const emu::MillingProcessParams& process, double depth_mm,
                                            std::size_t count) {
  emu::MillingProcess p(process);
  const std::vector<double> u = test_stage_input(count, 2.0, 1.0, 2, 7);
  std::vector<TestStageSample> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    out.push_back({p.force(), p.feed(), u[i]});
    p.step(u[i], depth_mm);
  }
  return out;
}

}  // namespace tnv::hil
