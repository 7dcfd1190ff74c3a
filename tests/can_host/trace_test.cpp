// CAN sessions as files: candump's log format both ways, the frames of a
// real session recorded by TracingBus, and every frame read by name.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/param_table.hpp"
#include "tools/can/candump_log.hpp"
#include "tools/can/frame_text.hpp"
#include "tools/can/node_client.hpp"
#include "tools/can/tracing_bus.hpp"
#include "tools/can_emu/emulated_bus.hpp"

namespace tnv {
namespace {

namespace can = fw::can;
using can_host::candump_line;
using can_host::parse_candump_line;

std::string scratch(const std::string& name) {
  const auto p = std::filesystem::temp_directory_path() / ("tnv_trace_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove(p);
  return p.string();
}

hal::CanFrame frame(std::uint32_t id, std::initializer_list<std::uint8_t> bytes, bool extended = false) {
  hal::CanFrame f;
  f.id = id;
  f.extended = extended;
  f.dlc = static_cast<std::uint8_t>(bytes.size());
  std::copy(bytes.begin(), bytes.end(), f.data.begin());
  return f;
}

TEST(CandumpLog, LinesRoundTripInCandumpsFormat) {
  const hal::CanFrame std_frame = frame(0x241, {0x11, 0x00, 0x16, 0x01, 0x00, 0x00, 0x80, 0x3E});
  EXPECT_EQ(candump_line(1700000000.25, "can0", std_frame), "(1700000000.250000) can0 241#110016010000803E");
  const hal::CanFrame ext = frame(0x1ABCDEF, {}, true);
  EXPECT_EQ(candump_line(0.5, "vcan1", ext), "(0.500000) vcan1 01ABCDEF#");
  for (const hal::CanFrame& f : {std_frame, ext}) {
    std::string error;
    const auto r = parse_candump_line(candump_line(12.000001, "emu", f), error);
    ASSERT_TRUE(r.has_value()) << error;
    EXPECT_DOUBLE_EQ(r->t_s, 12.000001);
    EXPECT_EQ(r->iface, "emu");
    EXPECT_EQ(r->frame.id, f.id);
    EXPECT_EQ(r->frame.extended, f.extended);
    EXPECT_EQ(r->frame.dlc, f.dlc);
    EXPECT_EQ(r->frame.data, f.data);
  }
}

TEST(CandumpLog, WhatIsNotOneClassicFrameIsRefusedWithItsReason) {
  const std::pair<const char*, const char*> bad[] = {
      {"", "expected"},
      {"241#00", "expected"},
      {"(x) can0 241#00", "timestamp"},
      {"(1.0) can0", "no interface"},
      {"(1.0) can0 24100", "'#'"},
      {"(1.0) can0 2410#00", "3 (standard) or 8"},
      {"(1.0) can0 24G#00", "not hex"},
      {"(1.0) can0 800#00", "out-of-range"},
      {"(1.0) can0 20000080#0000000000000000", "out-of-range"},  // an error frame
      {"(1.0) can0 241##1001122", "CAN FD"},
      {"(1.0) can0 241#R", "remote"},
      {"(1.0) can0 241#001", "hex pairs"},
      {"(1.0) can0 241#000102030405060708", "0 to 8 bytes"},
      {"(1.0) can0 241#0G", "not hex"},
  };
  for (const auto& [line, why] : bad) {
    std::string error;
    EXPECT_FALSE(parse_candump_line(line, error).has_value()) << line;
    EXPECT_NE(error.find(why), std::string::npos) << line << ": " << error;
  }
}

TEST(FrameText, ParameterValuesAreTypedByTheirParameterAndBitsNamed) {
  const can::ParamDef& gamma = *can::find_param("x.sliding.gamma");
  hal::CanFrame reply = can::make_frame(*can::classify(frame(0x121, {})), 1);  // PARAM_REPLY of node 1
  reply.dlc = 8;
  const can::MessageDef& m = *can::classify(reply);
  ASSERT_STREQ(m.name, "param_reply");
  for (const can::FieldDef& f : m.fields) {
    if (std::string_view(f.name) == "tag") can::write_raw(reply, f, 0x11);
    if (std::string_view(f.name) == "param") can::write_raw(reply, f, gamma.id);
    if (std::string_view(f.name) == "value") can::write_raw(reply, f, can::to_wire(gamma, 0.25));
  }
  const std::string text = can_host::frame_text(reply);
  EXPECT_NE(text.find("PARAM_REPLY node 1"), std::string::npos) << text;
  EXPECT_NE(text.find("result=ok"), std::string::npos) << text;
  EXPECT_NE(text.find("param=0x0116 (x.sliding.gamma)"), std::string::npos) << text;
  EXPECT_NE(text.find("value=0.25"), std::string::npos) << text;

  hal::CanFrame hb = can::make_frame(*can::classify(frame(0x181, {})), 1);  // HEARTBEAT of node 1
  for (const can::FieldDef& f : can::classify(hb)->fields) {
    if (std::string_view(f.name) == "errors") can::write_raw(hb, f, can::kHbParamsUnsaved | can::kHbCommissioning);
    if (std::string_view(f.name) == "axes")
      can::write_raw(hb, f, can::hb_homed_bit(hal::Axis::x) | can::hb_shaper_bit(hal::Axis::y));
  }
  const std::string hb_text = can_host::frame_text(hb);
  EXPECT_NE(hb_text.find("HEARTBEAT node 1"), std::string::npos) << hb_text;
  EXPECT_NE(hb_text.find("errors=[params_unsaved commissioning]"), std::string::npos) << hb_text;
  EXPECT_NE(hb_text.find("axes=[homed_x shaper_y]"), std::string::npos) << hb_text;
  EXPECT_NE(hb_text.find("state=disabled"), std::string::npos) << hb_text;

  EXPECT_NE(can_host::frame_text(frame(0x7FF, {1, 2})).find("not this protocol"), std::string::npos);
  EXPECT_NE(can_host::frame_text(frame(0x121, {1, 2})).find("short frame"), std::string::npos);
}

TEST(TracingBus, RecordsEveryFrameOfASessionBothWaysInOrder) {
  const std::string storage = scratch("params");
  const std::string trace = scratch("session.log");
  can_host::EmulatedNodeOptions o;
  o.storage_path = storage;
  std::string error;
  auto emulated = can_host::EmulatedBus::create(o, error);
  ASSERT_TRUE(emulated) << error;
  {
    can_host::TracingBus traced(*emulated, trace, "emu");
    can_host::NodeClient client(traced, 1);
    EXPECT_EQ(client.set(*can::find_param("x.sliding.gamma"), 0.25), 0.25);
  }
  std::ifstream in(trace);
  std::vector<can_host::CandumpRecord> records;
  for (std::string line; std::getline(in, line);) {
    const auto r = parse_candump_line(line, error);
    ASSERT_TRUE(r.has_value()) << line << ": " << error;
    records.push_back(*r);
  }
  // The set request, then (among heartbeats and telemetry) its reply, in time order.
  std::size_t request = records.size(), reply = records.size();
  for (std::size_t i = 0; i < records.size(); ++i) {
    const std::string text = can_host::frame_text(records[i].frame);
    if (text.find("PARAM_REQUEST") != std::string::npos && text.find("op=set") != std::string::npos) request = i;
    if (i > request && text.find("PARAM_REPLY") != std::string::npos && text.find("value=0.25") != std::string::npos)
      reply = std::min(reply, i);
    if (i > 0) {
      EXPECT_GE(records[i].t_s, records[i - 1].t_s);
    }
  }
  ASSERT_LT(request, records.size()) << "the set request was not recorded";
  EXPECT_LT(reply, records.size()) << "its reply was not recorded";
  EXPECT_THROW(can_host::TracingBus(*emulated, "/nonexistent-dir/x.log", "emu"), can_host::BusError);
  std::filesystem::remove(storage);
  std::filesystem::remove(trace);
}

}  // namespace
}  // namespace tnv
