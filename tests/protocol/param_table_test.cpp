// The parameter table: unique names, defaults valid and in range, values
// survive the wire, x and y describe the same things.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "firmware/can/capture_channels.hpp"
#include "firmware/can/param_table.hpp"
#include "hal/axis.hpp"

namespace {

using namespace tnv::fw::can;

TEST(ParamTable, NamesUniqueAndFoundByNameAndId) {
  std::set<std::string> names;
  for (const ParamDef& p : param_table()) {
    EXPECT_TRUE(names.insert(p.name).second) << p.name;
    EXPECT_EQ(find_param(p.id), &p);
    EXPECT_EQ(find_param(p.name), &p);
    EXPECT_LE(p.min, p.max) << p.name;
    EXPECT_EQ(p.set == nullptr, p.access == Access::read_only) << p.name;
  }
  EXPECT_EQ(find_param(std::uint16_t{0x7777}), nullptr);
  EXPECT_EQ(find_param("x.no.such"), nullptr);
}

TEST(ParamTable, DefaultsAreValidInRangeAndSurviveTheWire) {
  const NodeSettings d = default_node_settings();
  const SettingsCheck whole = validate(d);
  EXPECT_TRUE(whole.ok) << whole.section << ": " << whole.reason;
  for (const ParamDef& p : param_table()) {
    const double v = p.get(d);
    if (p.access == Access::read_write) {
      EXPECT_EQ(check_value(p, v), ErrorCode::ok) << p.name << " = " << v;
    }
    const double back = from_wire(p, to_wire(p, v));
    if (p.type == ParamType::f32) {
      EXPECT_EQ(back, static_cast<double>(static_cast<float>(v))) << p.name;
    } else {
      EXPECT_EQ(back, v) << p.name;
    }
  }
  EXPECT_EQ(find_param("sys.param_count")->get(d), static_cast<double>(param_table().size()));
  EXPECT_EQ(find_param("sys.protocol_version")->get(d), static_cast<double>(kProtocolVersion));
}

TEST(ParamTable, SetThenGetIsTheValue) {
  for (const ParamDef& p : param_table()) {
    if (p.access == Access::read_only) continue;
    NodeSettings s = default_node_settings();
    double v = p.type == ParamType::f32 ? p.min + 0.25 * (p.max - p.min) : std::floor(0.5 * (p.min + p.max));
    if (p.allowed != nullptr) v = p.max;
    ASSERT_EQ(check_value(p, v), ErrorCode::ok) << p.name;
    p.set(s, v);
    EXPECT_EQ(p.get(s), v) << p.name;
  }
}

TEST(ParamTable, CheckValueRefusesBadValues) {
  const ParamDef& q = *find_param("x.sliding.q");
  EXPECT_EQ(check_value(q, std::nan("")), ErrorCode::not_finite);
  EXPECT_EQ(check_value(q, std::numeric_limits<double>::infinity()), ErrorCode::not_finite);
  EXPECT_EQ(check_value(q, -std::numeric_limits<double>::infinity()), ErrorCode::not_finite);
  EXPECT_EQ(check_value(q, 1.5), ErrorCode::out_of_range);
  EXPECT_EQ(check_value(q, 0.5), ErrorCode::ok);
  EXPECT_EQ(check_value(*find_param("sys.protocol_version"), 1.0), ErrorCode::read_only);
  const ParamDef& node = *find_param("can.node_id");
  EXPECT_EQ(check_value(node, 0.0), ErrorCode::out_of_range);
  EXPECT_EQ(check_value(node, 2.5), ErrorCode::out_of_range) << "integers only";
  EXPECT_EQ(check_value(node, 31.0), ErrorCode::ok);
  EXPECT_EQ(check_value(node, 32.0), ErrorCode::out_of_range) << "the identifier has 5 bits of node id";
  const ParamDef& rate = *find_param("can.bitrate_kbit");
  EXPECT_EQ(check_value(rate, 500.0), ErrorCode::ok);
  EXPECT_EQ(check_value(rate, 300.0), ErrorCode::out_of_range) << "not a supported bit rate";
}

TEST(ParamTable, CrossFieldRulesNameTheParameter) {
  NodeSettings s = default_node_settings();
  s.firmware.axis[1].sliding.phi_mm_s = 0.01;  // below eta / (q + 1): Theorem 2
  const SettingsCheck c = validate(s);
  EXPECT_FALSE(c.ok);
  EXPECT_EQ(c.param, find_param("y.sliding.phi_mm_s")->id) << c.section << ": " << c.reason;
  s = default_node_settings();
  s.firmware.supervisor.axis[0].position_min_mm = 10.0;
  s.firmware.supervisor.axis[0].position_max_mm = 5.0;
  EXPECT_FALSE(validate(s).ok);
}

TEST(ParamTable, AxesMirrorEachOther) {
  std::size_t x_count = 0;
  for (const ParamDef& p : param_table()) {
    if ((p.id & 0xFF00) != 0x0100) continue;
    ++x_count;
    const ParamDef* y = find_param(static_cast<std::uint16_t>(0x0200 | (p.id & 0xFF)));
    ASSERT_NE(y, nullptr) << p.name << " has no y twin";
    EXPECT_STREQ(p.name + 2, y->name + 2);
    EXPECT_EQ(std::strncmp(p.name, "x.", 2), 0);
    EXPECT_EQ(std::strncmp(y->name, "y.", 2), 0);
    EXPECT_EQ(p.type, y->type);
    EXPECT_EQ(p.apply, y->apply);
  }
  EXPECT_GT(x_count, 30u);
}

TEST(ParamTable, EveryTunableTheIssueNamesIsThere) {
  for (const char* axis_name : tnv::hal::kAxisNames)
    for (const char* name : {"sliding.G_position_1_s", "sliding.eta_mm_s", "sliding.phi_mm_s", "sliding.q",
                             "sliding.g", "sliding.gamma", "pid.kp", "pid.ki", "pid.kd", "shaper.type",
                             "shaper.freq_hz", "shaper.zeta", "shaper.enable", "limits.position_min_mm",
                             "limits.following_floor_mm", "limits.following_lag_s"}) {
      std::string full = std::string(axis_name) + ".";
      full += name;
      EXPECT_NE(find_param(full.c_str()), nullptr) << full;
    }
  for (const char* name : {"can.node_id", "can.bitrate_kbit", "tlm.heartbeat_ms", "tlm.position_ms"})
    EXPECT_NE(find_param(name), nullptr) << name;
}

// The safety parameters are exactly the ones docs/safety.md "Commissioning"
// lists: every supervisor limit, the stall levels, the missed-tick limit,
// the host timeout, the jog dead man and the encoder and DAC scales.
TEST(ParamTable, SafetyParametersAreTheSupervisorsLimitsAndTheScales) {
  std::vector<std::string> safety;
  for (const ParamDef& p : param_table())
    if (safety_param(p)) safety.emplace_back(p.name);
  std::vector<std::string> expected = {"can.host_timeout_ms", "supervisor.max_missed_ticks"};
  for (const char* axis_name : tnv::hal::kAxisNames)
    for (const char* name : {"limits.position_min_mm", "limits.position_max_mm", "limits.speed_max_mm_s",
                             "limits.following_floor_mm", "limits.following_lag_s", "limits.stall_command_mm_s",
                             "limits.stall_ticks", "jog.deadman_s", "hw.count_mm", "hw.dac_full_scale_mm_s"})
      expected.push_back(std::string(axis_name) + "." + name);
  std::sort(safety.begin(), safety.end());
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(safety, expected);
  for (const ParamDef& p : param_table())
    if (safety_param(p)) {
      EXPECT_EQ(p.access, Access::read_write) << p.name;
    }
}

// The values the issue used to defeat the supervisor are outside the ranges.
TEST(ParamTable, TheIssuesAbuseIsOutOfRange) {
  const std::pair<const char*, double> abuse[] = {{"x.limits.following_floor_mm", 100.0},
                                                  {"x.limits.following_lag_s", 10.0},
                                                  {"x.limits.position_min_mm", -10000.0},
                                                  {"x.limits.position_max_mm", 10000.0},
                                                  {"supervisor.max_missed_ticks", 1000.0}};
  for (const auto& [name, value] : abuse) EXPECT_EQ(check_value(*find_param(name), value), ErrorCode::out_of_range) << name;
}

TEST(CaptureChannels, BitsAreDenseAndValuesAre32Bit) {
  for (std::size_t i = 0; i < kCaptureChannels.size(); ++i) {
    EXPECT_EQ(kCaptureChannels[i].bit, i);
    EXPECT_EQ(wire_size(kCaptureChannels[i].type), 4u) << kCaptureChannels[i].name;
    EXPECT_EQ(find_channel(static_cast<std::uint8_t>(i)), &kCaptureChannels[i]);
  }
  EXPECT_EQ(kDefaultCaptureChannels & ~kAllCaptureChannels, 0u);
}

}  // namespace
