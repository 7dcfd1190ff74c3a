// A refused parameter set names the parameter at fault by its id: the
// validators name the offending member, the parameter table knows which
// parameter each member is (no text is read back into an id).
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "firmware/can/node_settings.hpp"
#include "firmware/can/param_table.hpp"

namespace tnv::fw::can {
namespace {

std::uint16_t blamed_param_id(const char* name) {
  const ParamDef* p = find_param(name);
  return p != nullptr ? p->id : 0xFFFF;
}

// Every value in a parameter's range that the whole set refuses is
// refused naming a parameter (the forgettable step: a validator that names
// no member, or a member no parameter row points at).
TEST(ValidationNamesTheParameter, EveryRefusedValueInRangeNamesAParameter) {
  const NodeSettings base = default_node_settings();
  int refused = 0;
  for (const ParamDef& p : param_table()) {
    if (p.access != Access::read_write) continue;
    const double span = p.max - p.min;
    for (const double v : {p.min, p.max, p.min + 0.25 * span, p.min + 0.5 * span, p.min + 1e-3 * span}) {
      NodeSettings s = base;
      p.set(s, p.type == ParamType::f32 ? v : std::round(v));
      if (p.allowed != nullptr && !p.allowed(p.get(s))) continue;
      const SettingsCheck c = validate(s);
      if (c.ok) continue;
      ++refused;
      EXPECT_NE(c.param, 0) << p.name << " = " << v << " refused naming no parameter: " << c.section << ": "
                            << c.reason;
    }
  }
  EXPECT_GT(refused, 20) << "too few refusals exercised";
}

TEST(ValidationNamesTheParameter, CrossFieldRulesNameTheFieldTheirMessageIsAbout) {
  struct Case {
    const char* set;
    double value;
    const char* blamed;
  };
  const Case cases[] = {
      {"y.sliding.phi_mm_s", 0.01, "y.sliding.phi_mm_s"},      // phi > eta / (q + 1)
      {"x.sliding.gamma", 0.95, "x.sliding.gamma"},            // gamma < min(1 - g, q)
      {"x.homing.search_mm_s", 0.5, "x.homing.latch_mm_s"},    // latch (1 mm/s) <= search
      {"y.path.jerk_mm_s3", 10.0, "y.path.jerk_mm_s3"},        // the jerk filter's length: the axis that needs it
      {"arsc.override_min", 1.5, "arsc.override_min"},         // below override_max
      {"y.model.b2", 0.0, "y.pid.feedforward"},              // the feed-forward divides by B2: its switch is at fault
  };
  for (const Case& k : cases) {
    NodeSettings s = default_node_settings();
    const ParamDef* p = find_param(k.set);
    ASSERT_NE(p, nullptr) << k.set;
    p->set(s, k.value);
    const SettingsCheck c = validate(s);
    ASSERT_FALSE(c.ok) << k.set;
    EXPECT_EQ(c.param, blamed_param_id(k.blamed)) << k.set << ": " << c.section << ": " << c.reason;
  }
}

TEST(ValidationNamesTheParameter, EachMemberIsOneParameterAndLiesInTheSettings) {
  const NodeSettings s = default_node_settings();
  const auto* first = reinterpret_cast<const unsigned char*>(&s);
  std::set<const void*> seen;
  int members = 0;
  for (const ParamDef& p : param_table()) {
    if (p.member == nullptr) {
      EXPECT_EQ(p.set, nullptr) << p.name << ": a settable parameter is a member";
      continue;
    }
    ++members;
    const auto* at = static_cast<const unsigned char*>(p.member(s));
    EXPECT_TRUE(at >= first && at < first + sizeof(s)) << p.name;
    EXPECT_TRUE(seen.insert(p.member(s)).second) << p.name << " shares its member with another parameter";
  }
  EXPECT_GT(members, 100);
}

}  // namespace
}  // namespace tnv::fw::can
