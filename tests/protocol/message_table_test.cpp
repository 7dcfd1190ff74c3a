// The message table is well formed and every field round-trips through
// the codec the firmware and the host share.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <string_view>

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/program_tracker.hpp"
#include "firmware/can/protocol_messages.hpp"
#include "firmware/can/segment_wire.hpp"
#include "firmware/control/axis_controller.hpp"
#include "firmware/shaper/shaper_type.hpp"
#include "firmware/supervisor/fault.hpp"
#include "firmware/tick/tick_record.hpp"
#include "tools/protogen/text_format.hpp"

namespace {

using namespace tnv::fw::can;
using tnv::hal::CanFrame;

TEST(MessageTable, IdsAndNamesUniqueAndInRange) {
  std::set<int> ids;
  std::set<std::string> names;
  for (const MessageDef& m : kMessages) {
    EXPECT_LE(m.id, kMaxMessageId) << m.name;
    EXPECT_TRUE(ids.insert(m.id).second) << "duplicate id " << int(m.id);
    EXPECT_TRUE(names.insert(m.name).second) << "duplicate name " << m.name;
    EXPECT_LE(m.dlc, 8) << m.name;
  }
}

TEST(MessageTable, FieldsFitTheFrameAndDoNotOverlap) {
  for (const MessageDef& m : kMessages) {
    std::uint8_t used = 0;
    std::set<std::string> names;
    for (const FieldDef& f : m.fields) {
      EXPECT_TRUE(names.insert(f.name).second) << m.name << "." << f.name << " twice";
      const std::size_t n = wire_size(f.type);
      ASSERT_LE(f.byte_offset + n, m.dlc) << m.name << "." << f.name << " runs past the DLC";
      for (std::size_t b = f.byte_offset; b < f.byte_offset + n; ++b) {
        EXPECT_FALSE(used & (1u << b)) << m.name << "." << f.name << " overlaps at byte " << b;
        used = static_cast<std::uint8_t>(used | (1u << b));
      }
      EXPECT_GT(f.scale, 0.0) << m.name << "." << f.name;
    }
    // Fixed-length frames: every payload byte belongs to a field.
    EXPECT_EQ(used, static_cast<std::uint8_t>((1u << m.dlc) - 1u)) << m.name << " has unassigned bytes";
  }
}

// Values to try per type, in raw units.
std::vector<double> raw_samples(WireType t) {
  switch (t) {
    case WireType::u8: return {0, 1, 127, 255};
    case WireType::i8: return {-128, -1, 0, 1, 127};
    case WireType::u16: return {0, 1, 4660, 65535};
    case WireType::i16: return {-32768, -1, 0, 1, 32767};
    case WireType::u32:
    case WireType::raw32: return {0, 1, 305419896, 4294967295.0};
    case WireType::i32: return {-2147483648.0, -1, 0, 1, 2147483647.0};
    case WireType::f32: return {0.0, -0.0, 1.5, -123.25, 3.4028234663852886e38, 1e-30};
    case WireType::bytes7: return {};
    case WireType::u24: return {0, 1, 1193046, 16777215};
    case WireType::i24: return {-8388608, -1, 0, 1, 8388607};
  }
  return {};
}

TEST(MessageTable, EveryFieldRoundTrips) {
  for (const MessageDef& m : kMessages) {
    for (std::uint8_t node : {std::uint8_t{1}, kMaxNodeId}) {
      CanFrame frame = make_frame(m, node);
      EXPECT_EQ(frame.dlc, m.dlc);
      ASSERT_EQ(classify(frame), &m) << m.name;
      EXPECT_EQ(node_of(frame.id), node);
      for (const FieldDef& f : m.fields) {
        if (f.type == WireType::bytes7) {
          const std::array<std::uint8_t, 7> in{1, 2, 3, 250, 251, 252, 253};
          write_bytes(frame, f, in);
          std::array<std::uint8_t, 7> out{};
          read_bytes(frame, f, out);
          EXPECT_EQ(in, out) << m.name << "." << f.name;
          continue;
        }
        for (double raw : raw_samples(f.type)) {
          const double physical = raw * f.scale;
          ASSERT_TRUE(write(frame, f, physical)) << m.name << "." << f.name << " = " << physical;
          const double back = read(frame, f);
          if (f.type == WireType::f32) {
            EXPECT_EQ(back, static_cast<double>(static_cast<float>(physical)));
          } else {
            EXPECT_NEAR(back / f.scale, raw, 1e-6) << m.name << "." << f.name;
          }
        }
      }
      // Every field set at once: each reads back its own value (no byte shared).
      double k = 1.0;
      for (const FieldDef& f : m.fields)
        if (f.type != WireType::bytes7) write(frame, f, (k++) * f.scale);
      k = 1.0;
      for (const FieldDef& f : m.fields)
        if (f.type != WireType::bytes7) {
          EXPECT_NEAR(read(frame, f) / f.scale, k++, 1e-6) << m.name << "." << f.name;
        }
    }
  }
}

TEST(FrameCodec, IntegerFieldsRefuseWhatDoesNotFit) {
  const MessageDef& move = message(MessageId::move);
  const FieldDef& speed = field(move, "speed");  // u16, 0.01 mm/s
  CanFrame frame = make_frame(move, 1);
  EXPECT_TRUE(write(frame, speed, 655.35));
  EXPECT_FALSE(write(frame, speed, 655.36));
  EXPECT_FALSE(write(frame, speed, -0.01));
  EXPECT_FALSE(write(frame, speed, std::nan("")));
  EXPECT_FALSE(write(frame, speed, std::numeric_limits<double>::infinity()));
  EXPECT_NEAR(read(frame, speed), 655.35, 1e-9) << "a refused write must not change the frame";
  // f32 carries NaN and infinities so that the receiver can refuse them.
  const FieldDef& distance = field(move, "distance");
  EXPECT_TRUE(write(frame, distance, std::nan("")));
  EXPECT_TRUE(std::isnan(read(frame, distance)));
}

TEST(FrameCodec, ClassifyRejectsForeignFrames) {
  CanFrame f = make_frame(message(MessageId::heartbeat), 5);
  EXPECT_NE(classify(f), nullptr);
  f.extended = true;
  EXPECT_EQ(classify(f), nullptr);
  f.extended = false;
  f.id = make_can_id(0x1F, 5);  // unused message id
  EXPECT_EQ(classify(f), nullptr);
  f.id = 0x800;  // not an 11-bit identifier
  EXPECT_EQ(classify(f), nullptr);
}

TEST(FrameCodec, IdentifierLayout) {
  EXPECT_EQ(make_can_id(0x0C, 1), 0x181u);  // [10:5] message, [4:0] node
  EXPECT_EQ(message_of(0x181), 0x0C);
  EXPECT_EQ(node_of(0x181), 1);
  EXPECT_EQ(make_can_id(kMaxMessageId, kMaxNodeId), 0x7FFu) << "the whole 11-bit identifier";
  EXPECT_EQ(kMaxNodeId, 31);
  // CAN 2.0A forbids identifiers whose seven most significant bits are all recessive (0x7F0-0x7FF).
  for (const MessageDef& m : kMessages)
    for (std::uint8_t node = 0; node <= kMaxNodeId; ++node)
      EXPECT_LT(make_can_id(m.id, node), 0x7F0u) << m.name << " node " << int{node};
  // Priority: an e-stop to the highest node id beats telemetry of node 1.
  EXPECT_LT(make_can_id(static_cast<std::uint8_t>(MessageId::estop), kMaxNodeId),
            make_can_id(static_cast<std::uint8_t>(MessageId::tlm_position_x), 1));
}

// Lower id = higher priority: every request to the node but BORE_GAUGE (which
// waits between parts) and every answer ranks above every telemetry frame, and
// the capture upload ranks below everything.
TEST(FrameCodec, CommandsRankAboveTelemetryAndTheUploadLast) {
  std::uint8_t lowest_telemetry = kMaxMessageId;
  for (const MessageDef& m : kMessages)
    if (std::string_view(m.name).starts_with("tlm_")) lowest_telemetry = std::min(lowest_telemetry, m.id);
  for (const MessageDef& m : kMessages) {
    if (m.direction == Direction::to_node && m.id != static_cast<std::uint8_t>(MessageId::bore_gauge)) {
      EXPECT_LT(m.id, lowest_telemetry) << m.name;
    }
    if (m.id != static_cast<std::uint8_t>(MessageId::capture_data)) {
      EXPECT_LT(m.id, static_cast<std::uint8_t>(MessageId::capture_data)) << m.name;
    }
  }
}

// The value tables in the message table name the same things as the firmware enums.
template <typename Enum>
void expect_value_table(const char* values, int count, const char* what) {
  const auto table = tnv::protogen::value_table(values);
  ASSERT_EQ(static_cast<int>(table.size()), count) << what;
  for (int i = 0; i < count; ++i) {
    EXPECT_EQ(table[static_cast<std::size_t>(i)].first, i) << what;
    EXPECT_EQ(table[static_cast<std::size_t>(i)].second, to_string(static_cast<Enum>(i))) << what << " " << i;
  }
}

TEST(MessageTable, ValueTablesMatchTheEnums) {
  using tnv::fw::FaultReason;
  using tnv::fw::MotionState;
  int fault_count = 0;
  while (std::string(tnv::fw::to_string(static_cast<FaultReason>(fault_count))) != "?") ++fault_count;
  expect_value_table<FaultReason>(field(message(MessageId::heartbeat), "fault").values, fault_count, "fault");
  expect_value_table<MotionState>(field(message(MessageId::heartbeat), "state").values, 5, "state");
  expect_value_table<ErrorCode>(field(message(MessageId::param_reply), "result").values, kErrorCodeCount, "result");
  expect_value_table<CommandCode>(field(message(MessageId::command), "code").values, kCommandCodeCount, "command");
  expect_value_table<ProgramState>(field(message(MessageId::program_status), "state").values, 8, "program state");
  EXPECT_EQ(tnv::protogen::value_table(field(message(MessageId::segment), "kind").values).size(), kWireKindCount);
  expect_value_table<tnv::fw::ShaperType>(field(message(MessageId::shaper), "type").values,
                                          static_cast<int>(std::size(tnv::fw::kShaperTypes)), "shaper type");
  EXPECT_EQ(std::string(to_string(static_cast<ErrorCode>(kErrorCodeCount))), "?") << "kErrorCodeCount is stale";
  EXPECT_EQ(std::string(to_string(static_cast<CommandCode>(kCommandCodeCount))), "?") << "kCommandCodeCount is stale";
}

}  // namespace
