#pragma once
// A campaign's random numbers: its own generator (splitmix64) and its own
// inverse normal CDF, so a plan is the same on every compiler and standard
// library (std::normal_distribution is not). Only the plan draws numbers:
// the manifest keeps every resolved value, and runs and replays read them.
#include <cstdint>
#include <vector>

namespace tnv::campaign {

// splitmix64: one step of the generator, also a good 64-bit mix.
std::uint64_t splitmix64(std::uint64_t& state) noexcept;
std::uint64_t mix64(std::uint64_t value) noexcept;

// Uniform in (0, 1), never 0 or 1 (the inverse CDFs need an open interval).
double unit_open(std::uint64_t& state) noexcept;

// Phi^-1(p) for p in (0, 1): Acklam's rational approximation with one
// Halley step (relative error below 1e-15).
double inverse_normal_cdf(double p) noexcept;

enum class Sampling { random, latin_hypercube };

// runs x dims points in (0, 1)^dims, row-major. Latin hypercube: each
// dimension's N values fall one in each of the N strata [k/N, (k+1)/N).
std::vector<double> unit_samples(std::size_t runs, std::size_t dims, std::uint64_t seed, Sampling sampling);

}  // namespace tnv::campaign
