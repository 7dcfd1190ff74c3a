// Every per-axis table follows the axis list (hal/axis.hpp TNV_AXES): each
// axis has its parameter rows, capture channels, protocol fields, DBC
// signals and board registers, and the tables have nothing for an axis the
// list does not name. Adding an axis to the list without its rows fails here
// (or, for fixed-size wire layouts, at the static_asserts of the tables).
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <utility>

#include "firmware/can/capture_channels.hpp"
#include "firmware/can/param_table.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "firmware/can/protocol_messages.hpp"
#include "hal/axis.hpp"
#include "hal/io_board_registers.hpp"
#include "tools/protogen/dbc_writer.hpp"

namespace {

using namespace tnv;
using fw::can::kMessages;

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c);
  return s;
}

TEST(AxisList, NamesIndexesAndParsingAgree) {
  ASSERT_EQ(hal::kAxes.size(), hal::kAxisCount);
  std::set<std::string> names;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const hal::Axis a = hal::axis_from_index(i);
    EXPECT_EQ(hal::index(a), i);
    const std::string name = hal::axis_label(a);
    EXPECT_EQ(name.size(), 1u);
    EXPECT_EQ(hal::axis_name(a), name[0]);
    ASSERT_TRUE(hal::axis_from_name(name).has_value()) << name;
    EXPECT_EQ(*hal::axis_from_name(name), a);
    names.insert(name);
  }
  EXPECT_EQ(names.size(), hal::kAxisCount) << "axis names are distinct";
  EXPECT_FALSE(hal::axis_from_name("").has_value());
  EXPECT_FALSE(hal::axis_from_name("xy").has_value());
  EXPECT_FALSE(hal::axis_from_name("X").has_value()) << "names are lower case";
  EXPECT_FALSE(hal::axis_from_name("both").has_value());
  // The homing order holds every axis once; the set bits are the axes'.
  std::set<hal::Axis> homing(hal::kHomingOrder.begin(), hal::kHomingOrder.end());
  EXPECT_EQ(homing.size(), hal::kAxisCount);
  hal::AxisSet every = 0;
  for (const hal::Axis a : hal::kAxes) {
    EXPECT_TRUE(hal::contains(hal::kEveryAxis, a));
    EXPECT_EQ(every & hal::axis_bit(a), 0u);
    every |= hal::axis_bit(a);
  }
  EXPECT_EQ(every, hal::kEveryAxis);
  // The plane axes are two distinct axes of the list.
  EXPECT_NE(hal::kPlaneFirst, hal::kPlaneSecond);
  EXPECT_LT(hal::index(hal::kPlaneFirst), hal::kAxisCount);
  EXPECT_LT(hal::index(hal::kPlaneSecond), hal::kAxisCount);
}

// The rows of the first axis' block, by name without the "<axis>." prefix,
// are every axis' rows: same names, same offsets in the block, same types and
// ranges. Nothing else sits in an axis block.
TEST(AxisList, EveryAxisHasItsParameterRows) {
  const auto table = fw::can::param_table();
  std::map<std::string, const fw::can::ParamDef*> first_axis;
  const std::string first_prefix = std::string(hal::axis_label(hal::kAxes[0])) + ".";
  for (const auto& p : table)
    if (std::string_view(p.name).starts_with(first_prefix)) first_axis[std::string(p.name).substr(2)] = &p;
  ASSERT_GT(first_axis.size(), 10u);
  for (const hal::Axis a : hal::kAxes) {
    const std::uint16_t base = fw::can::axis_param_base(a);
    const std::string prefix = std::string(hal::axis_label(a)) + ".";
    std::size_t rows = 0;
    for (const auto& p : table) {
      const bool named = std::string_view(p.name).starts_with(prefix);
      const bool in_block = p.id >= base && p.id < base + 0x100;
      EXPECT_EQ(named, in_block) << p.name << " id " << p.id << ": an axis' rows are exactly its id block";
      if (!named) continue;
      ++rows;
      const auto it = first_axis.find(std::string(p.name).substr(2));
      ASSERT_NE(it, first_axis.end()) << p.name << " has no counterpart on the first axis";
      const fw::can::ParamDef& f = *it->second;
      EXPECT_EQ(p.id - base, f.id - fw::can::axis_param_base(hal::kAxes[0])) << p.name;
      EXPECT_EQ(p.type, f.type) << p.name;
      EXPECT_EQ(p.min, f.min) << p.name;
      EXPECT_EQ(p.max, f.max) << p.name;
      EXPECT_EQ(p.guard, f.guard) << p.name;
    }
    EXPECT_EQ(rows, first_axis.size()) << "axis " << hal::axis_label(a);
  }
  // No parameter block beyond the last axis'.
  const std::uint16_t past = fw::can::axis_param_base(hal::kAxes.back()) + 0x100;
  for (const auto& p : table) EXPECT_LT(p.id, past) << p.name;
}

// Every per-axis channel kind has one channel per axis, named <kind>_<axis>,
// and only those; bits are the channels' places.
TEST(AxisList, EveryAxisHasItsCaptureChannels) {
  std::map<fw::can::ChannelKind, std::set<std::uint8_t>> axes_of_kind;
  std::map<fw::can::ChannelKind, std::size_t> count_of_kind;
  for (std::size_t i = 0; i < fw::can::kCaptureChannels.size(); ++i) {
    const fw::can::ChannelDef& c = fw::can::kCaptureChannels[i];
    EXPECT_EQ(c.bit, i);
    ++count_of_kind[c.kind];
    const std::string name = c.name;
    const std::size_t us = name.rfind('_');
    if (us == std::string::npos) continue;
    const auto a = hal::axis_from_name(name.substr(us + 1));
    if (!a) continue;
    EXPECT_EQ(c.axis, hal::index(*a)) << name;
    axes_of_kind[c.kind].insert(c.axis);
  }
  ASSERT_GE(axes_of_kind.size(), 10u) << "position, reference, speed, command, s, d_hat, dac, unshaped, accel, excite";
  for (const auto& [kind, axes] : axes_of_kind) {
    EXPECT_EQ(axes.size(), hal::kAxisCount) << "kind " << static_cast<int>(kind);
    EXPECT_EQ(count_of_kind[kind], hal::kAxisCount) << "kind " << static_cast<int>(kind);
  }
}

const fw::can::MessageDef* message_named(std::string_view name) {
  for (const auto& m : kMessages)
    if (name == m.name) return &m;
  return nullptr;
}

bool has_field(const fw::can::MessageDef& m, std::string_view name) {
  for (const auto& f : m.fields)
    if (name == f.name) return true;
  return false;
}

// The per-axis protocol fields and messages, in the table and in the DBC.
TEST(AxisList, EveryAxisHasItsProtocolFieldsAndDbcSignals) {
  const std::string dbc = protogen::write_dbc(1);
  const auto block_of = [&dbc](const std::string& message) {
    std::string key(1, ' ');
    key += upper(message);
    key += ": ";
    const std::size_t at = dbc.find(key);
    if (at == std::string::npos) return std::string();
    return dbc.substr(at, dbc.find("\n\n", at) - at);
  };
  const std::string jog = block_of("jog"), heartbeat = block_of("heartbeat"), params = block_of("param_reply");
  ASSERT_FALSE(jog.empty());
  ASSERT_FALSE(params.empty());
  for (const hal::Axis a : hal::kAxes) {
    const std::string n = hal::axis_label(a);
    SCOPED_TRACE("axis " + n);
    // One message per axis of each per-axis block, at block base + axis index.
    const std::pair<const char*, const char*> blocks[] = {
        {"tlm_position_", " SG_ following :"}, {"tlm_sliding_", " SG_ s :"}, {"tlm_dac_", " SG_ code :"}};
    for (const auto& [prefix, signal] : blocks) {
      const fw::can::MessageDef* m = message_named(prefix + n);
      ASSERT_NE(m, nullptr) << prefix << n;
      const fw::can::MessageDef* first = message_named(prefix + std::string(hal::kAxisNames[0]));
      ASSERT_NE(first, nullptr);
      EXPECT_EQ(m->id, first->id + hal::index(a)) << prefix << n;
      EXPECT_NE(block_of(prefix + n).find(signal), std::string::npos) << prefix << n;
    }
    EXPECT_NE(heartbeat.find(" SG_ homed_" + n + " :"), std::string::npos);
    EXPECT_NE(heartbeat.find(" SG_ shaper_" + n + " :"), std::string::npos);
    EXPECT_NE(params.find(" SG_ " + n + "_controller m"), std::string::npos);
    // The axis fields' value lists name the axis with its index.
    const std::string value = std::to_string(hal::index(a)) + "=" + n;
    EXPECT_NE(std::string(fw::can::field(fw::can::message(fw::can::MessageId::move), "axis").values).find(value),
              std::string::npos);
    EXPECT_NE(std::string(fw::can::field(fw::can::message(fw::can::MessageId::command), "axis").values).find(value),
              std::string::npos);
  }
  // Nothing for an axis the list does not have: one message of each block per axis.
  for (const char* prefix : {"tlm_position_", "tlm_sliding_", "tlm_dac_"}) {
    std::size_t count = 0;
    for (const auto& m : kMessages) count += std::string_view(m.name).starts_with(prefix) ? 1 : 0;
    EXPECT_EQ(count, hal::kAxisCount) << prefix;
  }
  // JOG names its axis: its fields do not grow with the list.
  EXPECT_TRUE(has_field(*message_named("jog"), "axis"));
  EXPECT_TRUE(has_field(*message_named("jog"), "speed"));
  EXPECT_EQ(message_named("jog")->fields.size(), 3u);
  EXPECT_NE(jog.find(" SG_ speed :"), std::string::npos);
}

// The board: each axis has its own registers and bits, inside their windows.
TEST(AxisList, EveryAxisHasItsBoardRegisters) {
  namespace regs = hal::regs;
  std::set<std::uint32_t> words, inputs, faults, outputs;
  for (const hal::Axis a : hal::kAxes) {
    const regs::AxisRegisters& r = regs::axis_registers(a);
    for (const std::uint16_t w : {r.encoder, r.adc_accel, r.index}) {
      EXPECT_GE(w, regs::kSnapshotFirst);
      EXPECT_LT(w, regs::kSnapshotFirst + regs::kSnapshotWords);
      EXPECT_TRUE(words.insert(w).second) << w;
    }
    EXPECT_GE(r.dac, regs::kOutputFirst);
    EXPECT_LT(r.dac, regs::kOutputFirst + regs::kOutputWords);
    EXPECT_TRUE(words.insert(r.dac).second);
    for (const std::uint32_t b : {r.input_alarm, r.input_limit_pos, r.input_limit_neg, r.input_home})
      EXPECT_TRUE(b != 0 && inputs.insert(b).second) << b;
    for (const std::uint32_t b : {r.fault_encoder, r.fault_dac}) EXPECT_TRUE(b != 0 && faults.insert(b).second) << b;
    EXPECT_TRUE(r.output_enable != 0 && outputs.insert(r.output_enable).second);
  }
  EXPECT_EQ(words.size(), 4 * hal::kAxisCount);
  EXPECT_EQ(regs::all_axes(&regs::AxisRegisters::output_enable), [&] {
    std::uint32_t u = 0;
    for (const std::uint32_t b : outputs) u |= b;
    return u;
  }());
}

}  // namespace
