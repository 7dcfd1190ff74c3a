#include "firmware/shaper/grid_taps.hpp"

#include <cmath>
#include <numbers>

#include "firmware/shaper/small_linear_solve.hpp"

namespace tnv::fw {

namespace {

// Sample position of time t: whole part and fraction, with times that are
// on the grid to rounding snapped onto it.
struct GridPosition {
  std::uint32_t k = 0;
  double frac = 0.0;
};

GridPosition grid_position(double t_s, double period_s) noexcept {
  const double u = t_s / period_s;
  const double nearest = std::round(u);
  if (std::fabs(u - nearest) < 1e-9) return {static_cast<std::uint32_t>(nearest), 0.0};
  const double whole = std::floor(u);
  return {static_cast<std::uint32_t>(whole), u - whole};
}

// Double is enough: the solved taps meet the conditions to ~1e-16 (the
// tests check V at the mode); the systems are at most 9 x 9.
using Real = double;
constexpr std::size_t kMaxUnknowns = 16;   // 4 impulses x 4 candidate samples (TapSet: 2 x 16 convolved)
constexpr std::size_t kMaxConditions = 9;  // 1 + 2 x (3 + 1)

// The equality-constrained least-distance problem on the candidate samples.
struct GridProblem {
  std::size_t n = 0;           // candidate samples
  std::size_t conditions = 0;  // rows of C in use
  std::array<std::uint32_t, kMaxUnknowns> k{};
  std::array<Real, kMaxUnknowns> a0{};  // split amplitudes
  std::array<std::array<Real, kMaxUnknowns>, kMaxConditions> C{};
  std::array<Real, kMaxConditions> d{};
};

// C C^T over the active columns (the Gram matrix of the conditions on them).
SmallMatrix<Real, kMaxConditions> gram_of(const GridProblem& p, const std::array<bool, kMaxUnknowns>& active) noexcept {
  SmallMatrix<Real, kMaxConditions> gram{};
  for (std::size_t r = 0; r < p.conditions; ++r)
    for (std::size_t q = 0; q <= r; ++q) {
      Real sum = 0.0;
      for (std::size_t c = 0; c < p.n; ++c)
        if (active[c]) sum += p.C[r][c] * p.C[q][c];
      gram[r][q] = gram[q][r] = sum;
    }
  return gram;
}

// Minimum-norm correction of a0 on the active samples, given their C C^T
// (two passes: the second is iterative refinement, which also absorbs the
// rounding of a Gram matrix downdated column by column). False if C C^T is
// singular.
bool solve_active(const GridProblem& p, const std::array<bool, kMaxUnknowns>& active,
                  const SmallMatrix<Real, kMaxConditions>& gram, std::array<Real, kMaxUnknowns>& a) noexcept {
  std::array<std::size_t, kMaxUnknowns> cols{};
  std::size_t n_active = 0;
  for (std::size_t c = 0; c < p.n; ++c) {
    a[c] = active[c] ? p.a0[c] : 0.0;
    if (active[c]) cols[n_active++] = c;
  }
  for (int pass = 0; pass < 2; ++pass) {
    std::array<Real, kMaxConditions> y{};
    for (std::size_t r = 0; r < p.conditions; ++r) {
      Real acc = p.d[r];
      for (std::size_t i = 0; i < n_active; ++i) acc -= p.C[r][cols[i]] * a[cols[i]];
      y[r] = acc;
    }
    SmallMatrix<Real, kMaxConditions> CCt = gram;  // solve_in_place overwrites its matrix
    if (!solve_in_place(CCt, y, p.conditions)) return false;
    for (std::size_t i = 0; i < n_active; ++i)
      for (std::size_t r = 0; r < p.conditions; ++r) a[cols[i]] += p.C[r][cols[i]] * y[r];
  }
  return true;
}

enum class Sign { any, non_negative };

// Solves, and for Sign::non_negative drops the most negative tap and
// re-solves until none is left negative. False when that runs out of
// samples (or the system is singular). A dropped sample's column leaves
// C C^T by one rank-one downdate instead of a new sum over every column:
// this keeps a SHAPER command's design well inside the real-time budget
// (docs/safety.md).
bool solve(const GridProblem& p, Sign sign, std::array<Real, kMaxUnknowns>& a) noexcept {
  std::array<bool, kMaxUnknowns> active{};
  std::size_t n_active = p.n;
  for (std::size_t c = 0; c < p.n; ++c) active[c] = true;
  SmallMatrix<Real, kMaxConditions> gram = gram_of(p, active);
  while (n_active >= p.conditions) {
    if (!solve_active(p, active, gram, a)) return false;
    if (sign == Sign::any) return true;
    std::size_t worst = p.n;
    Real worst_a = -1e-15;  // rounding-level negatives are zeros
    for (std::size_t c = 0; c < p.n; ++c)
      if (active[c] && a[c] < worst_a) worst_a = a[(worst = c)];
    if (worst == p.n) return true;
    active[worst] = false;
    --n_active;
    for (std::size_t r = 0; r < p.conditions; ++r)
      for (std::size_t q = 0; q <= r; ++q) gram[r][q] = gram[q][r] = gram[r][q] - p.C[r][worst] * p.C[q][worst];
  }
  return false;
}

TapSet to_taps(const GridProblem& p, const std::array<Real, kMaxUnknowns>& a) noexcept {
  TapSet taps;
  for (std::size_t c = 0; c < p.n; ++c)
    if (std::fabs(a[c]) > 1e-15) taps.add(p.k[c], static_cast<double>(a[c]));
  return taps;
}

// Candidates, split start point and the conditions for J derivatives.
GridProblem make_problem(const ImpulseTrain& cont, const TapSet& split, const ModeSpec& mode, double period_s,
                         int derivatives) noexcept {
  GridProblem p;
  TapSet candidates;
  for (std::size_t i = 0; i < cont.count; ++i) {
    const GridPosition g = grid_position(cont.impulse[i].t_s, period_s);
    if (g.k > 0) candidates.add(g.k - 1, 0.0);
    for (std::uint32_t dk = 0; dk <= 2; ++dk) candidates.add(g.k + dk, 0.0);
  }
  p.n = candidates.count < kMaxUnknowns ? candidates.count : kMaxUnknowns;
  for (std::size_t c = 0; c < p.n; ++c) {
    p.k[c] = candidates.tap[c].k;
    for (std::size_t s = 0; s < split.count; ++s)
      if (split.tap[s].k == p.k[c]) p.a0[c] = split.tap[s].a;
  }
  p.conditions = 1 + 2 * static_cast<std::size_t>(derivatives);

  // Conditions in dimensionless time tau = (t - t_c) / T_d about the middle
  // of the shaper, so the rows are of similar size. Derivatives of
  // e^{s t_c} H(s) (same conditions: an invertible triangular mix of H's).
  const Real w = 2.0 * std::numbers::pi_v<Real> * static_cast<Real>(mode.freq_hz);
  const Real zeta = static_cast<Real>(mode.zeta);
  const Real sigma = zeta * w;
  const Real wd = w * std::sqrt(1.0 - zeta * zeta);
  const Real Td = 1.0 / (static_cast<Real>(mode.freq_hz) * std::sqrt(1.0 - zeta * zeta));
  const Real tc = 0.5 * static_cast<Real>(cont.duration_s());
  // Column of C for a unit impulse at t: row 0 is 1 (the sum); rows 2j+1,
  // 2j+2 are Re, Im of (-tau)^j e^{-p (t - t_c)} = (-tau)^j e^{sigma dt} e^{-i w_d dt}.
  const auto column = [&](Real t_s, std::array<Real, kMaxConditions>& out) {
    const Real dt = t_s - tc;
    const Real g = std::exp(sigma * dt);
    const Real re = g * std::cos(wd * dt), im = -g * std::sin(wd * dt);
    Real power = 1.0;  // (-tau)^j
    out[0] = 1.0;
    for (std::size_t j = 0; j < (p.conditions - 1) / 2; ++j) {
      out[2 * j + 1] = power * re;
      out[2 * j + 2] = power * im;
      power *= -dt / Td;
    }
  };
  std::array<Real, kMaxConditions> col{};
  for (std::size_t c = 0; c < p.n; ++c) {
    column(static_cast<Real>(p.k[c]) * static_cast<Real>(period_s), col);
    for (std::size_t r = 0; r < p.conditions; ++r) p.C[r][c] = col[r];
  }
  for (std::size_t i = 0; i < cont.count; ++i) {
    column(static_cast<Real>(cont.impulse[i].t_s), col);
    for (std::size_t r = 0; r < p.conditions; ++r) p.d[r] += static_cast<Real>(cont.impulse[i].a) * col[r];
  }
  p.d[0] = 1.0;  // the continuous sum is 1 to rounding; the taps' exactly
  return p;
}

}  // namespace

TapSet round_to_grid(const ImpulseTrain& train, double period_s) noexcept {
  TapSet taps;
  for (std::size_t i = 0; i < train.count; ++i)
    taps.add(static_cast<std::uint32_t>(std::llround(train.impulse[i].t_s / period_s)), train.impulse[i].a);
  return taps;
}

TapSet split_to_grid(const ImpulseTrain& train, double period_s) noexcept {
  TapSet taps;
  for (std::size_t i = 0; i < train.count; ++i) {
    const GridPosition g = grid_position(train.impulse[i].t_s, period_s);
    const double a = train.impulse[i].a;
    taps.add(g.k, a * (1.0 - g.frac));
    if (g.frac > 0.0) taps.add(g.k + 1, a * g.frac);
  }
  return taps;
}

TapSet exact_grid_taps(ShaperType type, const ModeSpec& mode, double period_s) noexcept {
  const ImpulseTrain cont = design_impulses(type, mode);
  const TapSet split = split_to_grid(cont, period_s);
  const int m = design_multiplicity(type);
  std::array<Real, kMaxUnknowns> a{};
  const GridProblem slope_kept = make_problem(cont, split, mode, period_s, m + 1);
  if (solve(slope_kept, Sign::non_negative, a)) return to_taps(slope_kept, a);
  const GridProblem zeros_only = make_problem(cont, split, mode, period_s, m);
  if (solve(zeros_only, Sign::non_negative, a)) return to_taps(zeros_only, a);
  if (solve(zeros_only, Sign::any, a)) return to_taps(zeros_only, a);
  return split;
}

}  // namespace tnv::fw
