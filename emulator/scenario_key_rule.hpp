#pragma once
// The range one scenario key must respect, on its own (the table's rule
// column, scenario_keys.cpp). Two steps, each optional, checked in order:
// a sign (finite, > 0, >= 0, >= 0 and below a limit, a positive multiple of
// 4), then a range with the reason it has ("must be 0..500: a ball screw's
// lost motion ..."). Rules between keys are code (scenario_validation.cpp).
#include <optional>
#include <string>
#include <utility>

namespace tnv::emu {

struct KeyRule {
  enum class Sign : unsigned char { any, finite, positive, non_negative, below, positive_multiple_of_4 };
  enum class Range : unsigned char {
    none,
    plausible,          // finite, low..high, with the reason
    zero_or_plausible,  // 0 (off), or low..high with the reason
    inf_or_plausible,   // +-inf (unbounded), or low..high (the reason in brackets)
    int_range,          // low..high
    at_least,           // >= low
    one_of,             // low or high; `reason` says what each means
    with_other_keys,    // no range of its own: checked against other keys (scenario_validation.cpp)
  };
  Sign sign = Sign::any;
  double limit = 0.0;  // Sign::below: value < limit
  Range range = Range::none;
  double low = 0.0;
  double high = 0.0;
  std::string text;  // Sign::below: what the limit is; Range: the reason

  // The message for `value` ("must be > 0 and finite (got -1)"), none if it is inside.
  std::optional<std::string> violation(double value) const;
  bool has_range() const noexcept { return sign != Sign::any || (range != Range::none && range != Range::with_other_keys); }

  // Chained onto a sign: positive().plausible(...).
  KeyRule plausible(double lo, double hi, std::string reason) const { return with(Range::plausible, lo, hi, std::move(reason)); }
  KeyRule int_range(double lo, double hi) const { return with(Range::int_range, lo, hi, {}); }

 private:
  KeyRule with(Range r, double lo, double hi, std::string reason) const {
    KeyRule out = *this;
    out.range = r;
    out.low = lo;
    out.high = hi;
    out.text = std::move(reason);
    return out;
  }
};

// The rules as the table writes them.
namespace key_rule {
inline KeyRule rule(KeyRule::Sign sign, double limit, KeyRule::Range range, double low, double high, std::string text) {
  KeyRule r;
  r.sign = sign;
  r.limit = limit;
  r.range = range;
  r.low = low;
  r.high = high;
  r.text = std::move(text);
  return r;
}
inline KeyRule sign(KeyRule::Sign s) { return rule(s, 0.0, KeyRule::Range::none, 0.0, 0.0, {}); }
inline KeyRule finite() { return sign(KeyRule::Sign::finite); }
inline KeyRule positive() { return sign(KeyRule::Sign::positive); }
inline KeyRule non_negative() { return sign(KeyRule::Sign::non_negative); }
inline KeyRule positive_multiple_of_4() { return sign(KeyRule::Sign::positive_multiple_of_4); }
// >= 0 and < limit; `what` names the limit in the message ("1", "the sub-step Nyquist ...").
inline KeyRule below(double limit, std::string what) {
  return rule(KeyRule::Sign::below, limit, KeyRule::Range::none, 0.0, 0.0, std::move(what));
}
inline KeyRule plausible(double low, double high, std::string reason) { return KeyRule{}.plausible(low, high, std::move(reason)); }
inline KeyRule zero_or_plausible(double low, double high, std::string reason) {
  return rule(KeyRule::Sign::any, 0.0, KeyRule::Range::zero_or_plausible, low, high, std::move(reason));
}
inline KeyRule inf_or_plausible(double low, double high, std::string reason) {
  return rule(KeyRule::Sign::any, 0.0, KeyRule::Range::inf_or_plausible, low, high, std::move(reason));
}
inline KeyRule int_range(double low, double high) { return KeyRule{}.int_range(low, high); }
inline KeyRule at_least(double low) { return rule(KeyRule::Sign::any, 0.0, KeyRule::Range::at_least, low, 0.0, {}); }
// `meaning`: "-1 (asserted at and below home_x_mm) or 1 (at and above)".
inline KeyRule one_of(double first, double second, std::string meaning) {
  return rule(KeyRule::Sign::any, 0.0, KeyRule::Range::one_of, first, second, std::move(meaning));
}
inline KeyRule with_other_keys() { return rule(KeyRule::Sign::any, 0.0, KeyRule::Range::with_other_keys, 0.0, 0.0, {}); }
}  // namespace key_rule

}  // namespace tnv::emu
