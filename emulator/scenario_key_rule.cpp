#include "emulator/scenario_key_rule.hpp"

#include <cmath>

#include "emulator/scenario_validation.hpp"

namespace tnv::emu {

namespace {

std::string whole(double value) { return std::to_string(static_cast<long long>(value)); }

std::optional<std::string> sign_violation(const KeyRule& r, double v) {
  switch (r.sign) {
    case KeyRule::Sign::any:
      return std::nullopt;
    case KeyRule::Sign::finite:
      if (!std::isfinite(v)) return "must be finite";
      return std::nullopt;
    case KeyRule::Sign::positive:
      if (!(std::isfinite(v) && v > 0.0)) return "must be > 0 and finite";
      return std::nullopt;
    case KeyRule::Sign::non_negative:
      if (!(std::isfinite(v) && v >= 0.0)) return "must be >= 0 and finite";
      return std::nullopt;
    case KeyRule::Sign::below:
      if (!(std::isfinite(v) && v >= 0.0 && v < r.limit)) return "must be >= 0 and below " + r.text;
      return std::nullopt;
    case KeyRule::Sign::positive_multiple_of_4:
      if (v <= 0.0 || std::fmod(v, 4.0) != 0.0) return "must be a positive multiple of 4 (x4 decoding)";
      return std::nullopt;
  }
  return std::nullopt;
}

std::optional<std::string> range_violation(const KeyRule& r, double v) {
  const std::string span = format_number(r.low) + ".." + format_number(r.high);
  const bool inside = v >= r.low && v <= r.high;  // false for NaN
  switch (r.range) {
    case KeyRule::Range::none:
    case KeyRule::Range::with_other_keys:
      return std::nullopt;
    case KeyRule::Range::plausible:
      if (!(std::isfinite(v) && inside)) return "must be " + span + ": " + r.text;
      return std::nullopt;
    case KeyRule::Range::zero_or_plausible:
      if (!(v == 0.0 || inside)) return "must be 0 (none) or " + span + ": " + r.text;
      return std::nullopt;
    case KeyRule::Range::inf_or_plausible:
      if (!(std::isinf(v) || inside)) return "must be " + span + " (" + r.text + ") or +-inf (unbounded)";
      return std::nullopt;
    case KeyRule::Range::int_range:
      if (v < r.low || v > r.high) return "must be in " + whole(r.low) + ".." + whole(r.high);
      return std::nullopt;
    case KeyRule::Range::at_least:
      if (v < r.low) return "must be >= " + whole(r.low);
      return std::nullopt;
    case KeyRule::Range::one_of:
      if (v != r.low && v != r.high) return "must be " + r.text;
      return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> KeyRule::violation(double value) const {
  std::optional<std::string> why = sign_violation(*this, value);
  if (!why) why = range_violation(*this, value);
  if (!why) return std::nullopt;
  return *why + " (got " + format_number(value) + ")";
}

}  // namespace tnv::emu
