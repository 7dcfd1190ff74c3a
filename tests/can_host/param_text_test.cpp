// Parameters as typed and printed by a person.
#include <gtest/gtest.h>

#include "hal/axis.hpp"
#include "tools/can/param_text.hpp"

namespace tnv {
namespace {

namespace can = fw::can;
using can_host::parse_param_value;

const can::ParamDef& param_def(const char* name) { return *can::find_param(name); }

TEST(ParamText, EnumsAndBooleansByNameNumbersAsNumbers) {
  std::string error;
  EXPECT_EQ(parse_param_value(param_def("x.controller"), "pid", error), 0.0);
  EXPECT_EQ(parse_param_value(param_def("x.controller"), "2", error), 2.0);
  EXPECT_EQ(parse_param_value(param_def("y.shaper.enable"), "on", error), 1.0);
  EXPECT_EQ(parse_param_value(param_def("y.shaper.enable"), "false", error), 0.0);
  EXPECT_EQ(parse_param_value(param_def("x.sliding.gamma"), "0.25", error), 0.25);
  EXPECT_EQ(parse_param_value(param_def("capture.channels"), "0x8001", error), 32769.0);
}

TEST(ParamText, RefusalsNameTheParameterAndTheAllowedValues) {
  std::string error;
  EXPECT_FALSE(parse_param_value(param_def("x.controller"), "fuzzy", error));
  EXPECT_EQ(error, "x.controller: 'fuzzy' is not a value of {pid, dvsc, rdvsc}");
  EXPECT_FALSE(parse_param_value(param_def("x.sliding.gamma"), "1.5", error));
  EXPECT_EQ(error, "x.sliding.gamma: 1.5 is outside 0 .. 1");
  EXPECT_FALSE(parse_param_value(param_def("x.sliding.gamma"), "nan", error));
  EXPECT_EQ(error, "x.sliding.gamma: not a finite number");
  EXPECT_FALSE(parse_param_value(param_def("can.bitrate_kbit"), "300", error));
  EXPECT_NE(error.find("{125, 250, 500, 1000}"), std::string::npos) << error;
  EXPECT_FALSE(parse_param_value(param_def("tlm.heartbeat_ms"), "2.5", error));
  EXPECT_NE(error.find("whole numbers"), std::string::npos) << error;
  EXPECT_FALSE(parse_param_value(param_def("sys.protocol_version"), "2", error));
  EXPECT_EQ(error, "sys.protocol_version: read-only");
}

TEST(ParamText, Float32ValuesPrintAsTheShortestTextThatReadsBack) {
  EXPECT_EQ(can_host::format_param_value(param_def("x.sliding.gamma"), static_cast<double>(0.4155f)), "0.4155");
  EXPECT_EQ(can_host::format_param_value(param_def("x.sliding.gamma"), 0.25), "0.25");
  EXPECT_EQ(can_host::format_param_value(param_def("x.controller"), 1), "dvsc");
  EXPECT_EQ(can_host::format_param_value(param_def("tlm.heartbeat_ms"), 100), "100");
}

TEST(ParamText, FindsByNameOrIdAndSuggestsCloseNames) {
  EXPECT_EQ(can_host::find_param_by_text("x.sliding.gamma"), &param_def("x.sliding.gamma"));
  EXPECT_EQ(can_host::find_param_by_text("0x0116"), &param_def("x.sliding.gamma"));
  EXPECT_EQ(can_host::find_param_by_text("x.sliding.gama"), nullptr);
  EXPECT_EQ(can_host::closest_param_name("x.sliding.gama"), "x.sliding.gamma");
  EXPECT_EQ(can_host::closest_param_name("completely.different"), "");
}

TEST(ParamText, GlobsAndGroupPrefixesExpandInTableOrder) {
  using can_host::params_matching;
  // One exact name or id: that parameter alone.
  ASSERT_EQ(params_matching("x.sliding.gamma").size(), 1u);
  EXPECT_EQ(params_matching("0x0116")[0], &param_def("x.sliding.gamma"));
  // A glob: every axis' gamma, X's first (table order).
  const auto gammas = params_matching("?.sliding.gamma");
  ASSERT_EQ(gammas.size(), hal::kAxisCount);
  EXPECT_STREQ(gammas[0]->name, "x.sliding.gamma");
  EXPECT_STREQ(gammas[1]->name, "y.sliding.gamma");
  EXPECT_STREQ(gammas[2]->name, "z.sliding.gamma");
  // A group prefix, with or without its dot; each member starts with it and the table has no other.
  const auto group = params_matching("x.sliding");
  EXPECT_EQ(group, params_matching("x.sliding."));
  std::size_t in_table = 0;
  for (const can::ParamDef& p : can::param_table())
    if (std::string_view(p.name).starts_with("x.sliding.")) ++in_table;
  EXPECT_GE(group.size(), 2u);
  EXPECT_EQ(group.size(), in_table);
  for (std::size_t i = 1; i < group.size(); ++i) EXPECT_LT(group[i - 1]->id, group[i]->id);
  // A prefix is a whole dotted group, never part of a word; nothing matched is empty.
  EXPECT_TRUE(params_matching("x.slid").empty());
  EXPECT_TRUE(params_matching("w.*").empty());
  EXPECT_TRUE(params_matching("").empty());
}

}  // namespace
}  // namespace tnv
