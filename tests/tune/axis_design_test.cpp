// The design rule without a table (tools/tune/axis_design.hpp): a failed
// identification is refused with its reason. The rule on identified
// emulated tables is tests/hil/autotune_design_test.cpp.
#include <gtest/gtest.h>

#include <string>

#include "tools/tune/axis_design.hpp"

namespace tnv::tune {
namespace {

TEST(AxisDesign, RefusesAFailedIdentification) {
  AxisIdentification id;
  id.error = "no data";
  const AxisDesign d = design_axis(id);
  EXPECT_FALSE(d.ok);
  EXPECT_NE(d.error.find("no data"), std::string::npos);
}

}  // namespace
}  // namespace tnv::tune
