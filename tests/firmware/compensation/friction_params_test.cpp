// The friction feed-forward's CAN parameters (issue 7): in the table,
// idle-only, off by default, and a set that breaks f_s >= f_c is refused
// naming the friction parameter, not some other one.
#include <gtest/gtest.h>

#include <cmath>

#include "firmware/can/node_settings.hpp"
#include "firmware/can/param_table.hpp"

namespace tnv::fw::can {
namespace {

TEST(FrictionParams, InTheTableIdleOnlyAndOffByDefault) {
  const NodeSettings s = default_node_settings();
  for (const char* name : {"x.friction.enable", "y.friction.enable", "x.friction.coulomb_mm_s", "y.friction.fraction"}) {
    const ParamDef* p = find_param(name);
    ASSERT_NE(p, nullptr) << name;
    EXPECT_EQ(p->apply, Apply::idle) << name;
  }
  EXPECT_EQ(find_param("x.friction.enable")->get(s), 0.0);
  EXPECT_EQ(find_param("y.friction.enable")->get(s), 0.0);
}

TEST(FrictionParams, BadSetIsRefusedNamingTheFrictionParameter) {
  NodeSettings s = default_node_settings();
  find_param("y.friction.coulomb_mm_s")->set(s, 2.0);
  find_param("y.friction.stiction_mm_s")->set(s, 1.0);  // below f_c
  const SettingsCheck c = validate(s);
  EXPECT_FALSE(c.ok);
  EXPECT_EQ(c.param, find_param("y.friction.stiction_mm_s")->id) << c.section << ": " << c.reason;
}

}  // namespace
}  // namespace tnv::fw::can
