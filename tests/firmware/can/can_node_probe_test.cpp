// Probe moves over CAN (protocol 10): a SEGMENT probe kind is queued as a
// probe line, nothing is taken behind it until its outcome (probe_pending,
// the queue unchanged), and the outcome goes out as PROBE_RESULT,
// PROBE_RESULT_Z and PROBE_REST with the same count. The fake table stands
// still, so the probe here is one whose input already is in the tripping
// state: refused at its start, an error that stops the program.
#include <gtest/gtest.h>

#include <vector>

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/segment_wire.hpp"
#include "tests/firmware/can/node_bench.hpp"

namespace tnv::test {
namespace {

namespace can = fw::can;
namespace motion = fw::motion;

const hal::CanFrame* find_frame(const std::vector<hal::CanFrame>& frames, can::MessageId id) {
  for (const hal::CanFrame& f : frames)
    if (is(f, id)) return &f;
  return nullptr;
}

// The element's frames, the last request's answers.
std::vector<hal::CanFrame> send_element(NodeBench& b, const motion::Segment& s) {
  can::SegmentFrames f;
  EXPECT_EQ(can::encode_segment(s, b.task.next_segment_start_mm(), kNode, kTestTag, f), nullptr);
  b.request(f.head);
  if (f.has_z) b.request(f.z);
  return b.request(f.tail);
}

TEST(CanNodeProbe, AProbeIsQueuedNothingFollowsItAndItsOutcomeIsReported) {
  NodeBench b;
  ASSERT_EQ(ack_result(b.reply(command(kNode, can::CommandCode::enable))), can::ErrorCode::ok);
  b.step();
  b.board.in.probe = true;  // touching already: a G38.3 toward the stock is refused at its start
  motion::PlanePoint end = b.task.next_segment_start_mm();
  end[hal::index(hal::Axis::z)] -= 5.0;
  std::vector<hal::CanFrame> out = send_element(b, motion::probe_to(motion::ProbeKind::toward, end, 2.0));
  ASSERT_EQ(out.size(), 3u) << "an ack, PROGRAM_STATUS and PROGRAM_TOOL";
  EXPECT_EQ(ack_result(out[0]), can::ErrorCode::ok);
  ASSERT_TRUE(b.task.motion().probe_pending());
  // A line behind it is refused, and the queue keeps only the probe.
  motion::PlanePoint next = b.task.next_segment_start_mm();
  next[0] += 1.0;
  out = send_element(b, motion::line_to(next, 10.0));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(ack_result(out[0]), can::ErrorCode::probe_pending);
  EXPECT_EQ(b.task.motion().queued(), 1u);
  // Its outcome: three frames, the same count.
  std::vector<hal::CanFrame> sent;
  for (int t = 0; t < 200 && find_frame(sent, can::MessageId::probe_result) == nullptr; ++t) {
    b.step();
    for (const hal::CanFrame& f : b.port.drain()) sent.push_back(f);
  }
  const hal::CanFrame* r = find_frame(sent, can::MessageId::probe_result);
  const hal::CanFrame* rz = find_frame(sent, can::MessageId::probe_result_z);
  const hal::CanFrame* rest = find_frame(sent, can::MessageId::probe_rest);
  ASSERT_TRUE(r != nullptr && rz != nullptr && rest != nullptr) << "the result's three frames";
  EXPECT_EQ(can::read_raw(*r, can::fields::kProbeCount), 1u);
  EXPECT_EQ(can::read_raw(*rz, can::fields::kProbeZCount), 1u);
  EXPECT_EQ(can::read_raw(*rest, can::fields::kProbeRestCount), 1u);
  EXPECT_EQ(can::read_raw(*r, can::fields::kProbeOutcome),
            static_cast<std::uint32_t>(motion::ProbeOutcome::already_tripped));
  // Refused at its start: trip and rest are where it stood.
  const motion::PlanePoint start = b.task.probe_report().rest_mm;
  EXPECT_NEAR(can::read(*r, can::fields::kProbeTripX), start[0], 1e-4);
  EXPECT_NEAR(can::read(*rest, can::fields::kProbeRestX), start[0], 1e-4);
  EXPECT_NEAR(can::read(*rz, can::fields::kProbeRestZ), start[hal::index(hal::Axis::z)], 1e-4);
  for (int t = 0; t < 200 && b.task.program_running(); ++t) b.step();
  EXPECT_FALSE(b.task.program_running()) << "an error outcome stops the program";
}

}  // namespace
}  // namespace tnv::test
