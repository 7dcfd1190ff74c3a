// SEGMENT / SEGMENT_TAIL on the node: an element is acknowledged with the
// queue's free slots once complete; every refusal names its code and the
// field at fault and leaves the queue as it was; only the command owner
// streams; HEARTBEAT and PROGRAM_STATUS carry the flow control.
#include <gtest/gtest.h>

#include <array>

#include "tests/hil/program_frames.hpp"

namespace tnv::test {
namespace {

namespace can = fw::can;
using can::CommandCode;
using can::ErrorCode;
using can::MessageId;
using fw::motion::PlanePoint;
namespace fld = can::fields;

constexpr auto code(ErrorCode e) { return static_cast<std::uint32_t>(e); }
constexpr std::uint32_t kSegment = static_cast<std::uint32_t>(MessageId::segment);
constexpr std::uint32_t kTail = static_cast<std::uint32_t>(MessageId::segment_tail);


PlanePoint offset(const PlanePoint& p, double dx, double dy) {
  PlanePoint q = p;  // Z (and any axis beyond the plane) where it is
  q[0] += dx;
  q[1] += dy;
  return q;
}

// A point's XY coordinates.
std::array<double, 2> plane(const PlanePoint& p) { return {p[0], p[1]}; }

TEST(CanNodeSegments, ALineWaitsForItsTailThenTheAckCarriesTheFreeSlots) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  ProgramHost host(*r);
  const can::SegmentFrames f = host.frames(fw::motion::line_to(offset(host.at_mm(), 5.0, 0.0), 10.0));
  EXPECT_TRUE(host.send_frames({f.head}).empty()) << "a line's SEGMENT alone is not answered";
  EXPECT_TRUE(r->node->segment_pending());
  const std::vector<ElementAck> acks = host.send_frames({f.tail});
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].result, kOk);
  EXPECT_EQ(acks[0].request, kTail);
  EXPECT_EQ(acks[0].tag, f.tail.data[0]);
  EXPECT_EQ(acks[0].free_slots, fw::motion::kSegmentQueueCapacity - 1);
  EXPECT_TRUE(r->task().program_running());
  EXPECT_EQ(r->task().motion().queued(), 1u);

  const std::vector<ElementAck> dwell = host.send(fw::motion::dwell_for(0.5));
  ASSERT_EQ(dwell.size(), 1u) << "a dwell is one frame";
  EXPECT_EQ(dwell[0].request, kSegment);
  EXPECT_EQ(dwell[0].free_slots, r->task().motion().free_slots());
}

struct BadElement {
  const char* what;
  fw::motion::Segment segment;
  ErrorCode code;
  std::uint32_t request;
  const can::FieldDef* field;  // nullptr: detail 0
};

TEST(CanNodeSegments, EveryRefusalNamesItsCodeAndFieldAndLeavesTheQueueUnchanged) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  ProgramHost host(*r);
  ASSERT_EQ(host.send(fw::motion::line_to(offset(host.at_mm(), 2.0, 0.0), 10.0)).at(0).result, kOk);
  const PlanePoint at = host.at_mm();
  const std::vector<BadElement> bad = {
      {"zero length", fw::motion::line_to(at, 10.0), ErrorCode::zero_length, kSegment, &fld::kSegmentX},
      {"outside the workspace", fw::motion::line_to({300.0, at[1]}, 10.0), ErrorCode::outside_workspace, kSegment,
       &fld::kSegmentX},
      {"feed above the axis limit", fw::motion::line_to(offset(at, 5.0, 0.0), 150.0), ErrorCode::feed_above_limit,
       kTail, &fld::kTailFeed},
      {"arc radius mismatch", fw::motion::arc_to(false, offset(at, 10.0, 0.0), offset(at, 5.1, 0.0), 10.0),
       ErrorCode::bad_arc, kTail, &fld::kTailCentreNormal},
      {"arc radius below the minimum", fw::motion::arc_to(false, offset(at, 0.004, 0.0), offset(at, 0.002, 0.0), 1.0),
       ErrorCode::bad_arc, kTail, &fld::kTailCentreNormal},
  };
  for (const BadElement& b : bad) {
    SCOPED_TRACE(b.what);
    const std::size_t queued = r->task().motion().queued();
    const std::vector<ElementAck> acks = host.send(b.segment);
    ASSERT_EQ(acks.size(), 1u);
    EXPECT_EQ(acks[0].result, code(b.code)) << can::to_string(static_cast<ErrorCode>(acks[0].result));
    EXPECT_EQ(acks[0].request, b.request);
    const can::MessageDef& m = b.request == kSegment ? fld::kSegmentMsg : fld::kSegmentTailMsg;
    EXPECT_EQ(acks[0].detail, b.field != nullptr ? fld::index_of(m, *b.field) : 0u);
    EXPECT_EQ(r->task().motion().queued(), queued) << "a refused element must not be queued";
    EXPECT_EQ(acks[0].free_slots, r->task().motion().free_slots());
    EXPECT_EQ(plane(r->task().motion().queue_end_mm()), plane(at)) << "the next element still starts where the last accepted one ended";
  }
  // A negative dwell (the host's encoder never writes one).
  can::SegmentFrames f = host.frames(fw::motion::dwell_for(1.0));
  can::write(f.head, fld::kSegmentX, -0.5);
  std::vector<ElementAck> acks = host.send_frames({f.head});
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].result, code(ErrorCode::out_of_range));
  EXPECT_EQ(acks[0].detail, fld::index_of(fld::kSegmentMsg, fld::kSegmentX));
  // A kind the node does not know.
  f = host.frames(fw::motion::dwell_for(1.0));
  can::write_raw(f.head, fld::kSegmentKind, can::kWireKindCount);
  acks = host.send_frames({f.head});
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].result, code(ErrorCode::out_of_range));
  EXPECT_EQ(acks[0].detail, fld::index_of(fld::kSegmentMsg, fld::kSegmentKind));
  // A tail without its head, and a head whose tail never came: both answered not_ready.
  f = host.frames(fw::motion::line_to(offset(at, 1.0, 1.0), 5.0));
  acks = host.send_frames({f.tail});
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].result, code(ErrorCode::not_ready));
  const can::SegmentFrames g = host.frames(fw::motion::line_to(offset(at, 2.0, 1.0), 5.0));
  acks = host.send_frames({f.head, g.head, g.tail});
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_EQ(acks[0].tag, f.head.data[0]);
  EXPECT_EQ(acks[0].result, code(ErrorCode::not_ready)) << "the head left without a tail";
  EXPECT_EQ(acks[1].tag, g.head.data[0]);
  EXPECT_EQ(acks[1].result, kOk) << "the next element is whole";
  EXPECT_FALSE(r->task().fault().active());
}

TEST(CanNodeSegments, AZFrameCompletesItsElementAndAloneIsRefused) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  ProgramHost host(*r);
  const PlanePoint at = host.at_mm();
  PlanePoint down = offset(at, 3.0, 0.0);
  down[can::kProgramZ] = at[can::kProgramZ] - 2.0;
  const can::SegmentFrames f = host.frames(fw::motion::line_to(down, 5.0));
  ASSERT_TRUE(f.has_z);
  // The Z frame with no SEGMENT waiting: not_ready, nothing queued.
  std::vector<ElementAck> acks = host.send_frames({f.z});
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].result, code(ErrorCode::not_ready));
  EXPECT_EQ(acks[0].request, static_cast<std::uint32_t>(MessageId::segment_z));
  EXPECT_EQ(r->task().motion().queued(), 0u);
  // Twice for one element: that element is refused whole, and its tail finds nothing waiting.
  acks = host.send_frames({f.head, f.z, f.z, f.tail});
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_EQ(acks[0].result, code(ErrorCode::not_ready));
  EXPECT_EQ(acks[1].result, code(ErrorCode::not_ready));
  EXPECT_EQ(r->task().motion().queued(), 0u);
  EXPECT_FALSE(r->node->segment_pending());
  // Whole: accepted, and the queue ends at its Z; the next element in the plane stays at that Z.
  acks = host.send(fw::motion::line_to(down, 5.0));
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].result, kOk);
  EXPECT_NEAR(r->task().motion().queue_end_mm()[can::kProgramZ], down[can::kProgramZ], 1e-4);
  PlanePoint along = offset(host.at_mm(), 2.0, 1.0);
  acks = host.send(fw::motion::line_to(along, 5.0));
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].result, kOk);
  EXPECT_NEAR(r->task().motion().queue_end_mm()[can::kProgramZ], down[can::kProgramZ], 1e-4);
  // Below Z's soft limit: refused by the queue, the queue unchanged.
  PlanePoint deep = host.at_mm();
  deep[can::kProgramZ] = -700.0;
  const std::size_t queued = r->task().motion().queued();
  acks = host.send(fw::motion::line_to(deep, 5.0));
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].result, code(ErrorCode::outside_workspace));
  EXPECT_EQ(r->task().motion().queued(), queued);
}

// An arc in G18 (protocol 9): SEGMENT, SEGMENT_PLANE, SEGMENT_TAIL. A
// plane the node does not know refuses the element whole, naming `plane`.
TEST(CanNodeSegments, AnArcInG18IsQueuedInItsPlaneAndAnUnknownPlaneRefusesItsElement) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  ProgramHost host(*r);
  const PlanePoint at = host.at_mm();
  // A quarter from the top of a circle in ZX towards +X (counter-clockwise in G18), Y 1 mm along: a helix.
  PlanePoint centre = at;
  centre[can::kProgramZ] -= 5.0;
  PlanePoint end = offset(at, 5.0, 1.0);
  end[can::kProgramZ] -= 5.0;
  const fw::motion::Segment arc = fw::motion::arc_to(false, end, centre, 5.0, 0, fw::motion::ArcPlane::zx);
  can::SegmentFrames f = host.frames(arc);
  ASSERT_TRUE(f.has_z);
  ASSERT_EQ(f.z.dlc, fld::kSegmentPlaneMsg.dlc);
  hal::CanFrame unknown = f.z;
  unknown.data[fld::kPlaneField.byte_offset] = fw::motion::kArcPlaneCount;
  std::vector<ElementAck> acks = host.send_frames({f.head, unknown, f.tail});
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_EQ(acks[0].request, static_cast<std::uint32_t>(MessageId::segment_plane));
  EXPECT_EQ(acks[0].result, code(ErrorCode::out_of_range));
  EXPECT_EQ(acks[0].detail, fld::index_of(fld::kSegmentPlaneMsg, fld::kPlaneField));
  EXPECT_EQ(acks[1].result, code(ErrorCode::not_ready)) << "its tail finds nothing waiting";
  EXPECT_EQ(r->task().motion().queued(), 0u);
  EXPECT_FALSE(r->node->segment_pending());
  // A plane for a line: refused the same way.
  PlanePoint along = offset(at, 1.0, 0.0);
  can::SegmentFrames line = host.frames(fw::motion::line_to(along, 5.0));
  hal::CanFrame plane_of_line = f.z;
  plane_of_line.data[0] = line.head.data[0];
  acks = host.send_frames({line.head, plane_of_line, line.tail});
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_EQ(acks[0].result, code(ErrorCode::out_of_range));
  EXPECT_EQ(r->task().motion().queued(), 0u);
  // Whole: queued as a G18 arc ending where it was sent.
  acks = host.send(arc);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].result, kOk);
  EXPECT_EQ(r->task().motion().queued(), 1u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(r->task().motion().queue_end_mm()[i], end[i], 1e-4) << i;
}

TEST(CanNodeSegments, AFullQueueRefusesWithQueueFullAndKeepsEveryElement) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  ProgramHost host(*r);
  for (std::size_t k = 0; k < fw::motion::kSegmentQueueCapacity; ++k) {
    const std::vector<ElementAck> acks = host.send(fw::motion::dwell_for(10.0));
    ASSERT_EQ(acks.size(), 1u);
    ASSERT_EQ(acks[0].result, kOk) << "element " << k;
    ASSERT_EQ(acks[0].free_slots, fw::motion::kSegmentQueueCapacity - 1 - k);
  }
  const std::vector<ElementAck> acks = host.send(fw::motion::line_to(offset(host.at_mm(), 1.0, 0.0), 5.0));
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].result, code(ErrorCode::queue_full));
  EXPECT_EQ(acks[0].free_slots, 0u);
  EXPECT_EQ(r->task().motion().queued(), fw::motion::kSegmentQueueCapacity);
}

TEST(CanNodeSegments, OnlyTheCommandOwnerStreams) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  ProgramHost owner(*r, 1);
  ProgramHost other(*r, 2);
  const can::SegmentFrames mine = owner.frames(fw::motion::line_to(offset(owner.at_mm(), 3.0, 0.0), 10.0));
  ASSERT_TRUE(owner.send_frames({mine.head}).empty());
  // Host 2 streams a whole element in between: both frames refused, the owner's half kept.
  const can::SegmentFrames theirs = other.frames(fw::motion::line_to(offset(other.at_mm(), 0.0, 3.0), 10.0));
  const std::vector<ElementAck> refused = other.send_frames({theirs.head, theirs.tail});
  ASSERT_EQ(refused.size(), 2u);
  for (const ElementAck& a : refused) EXPECT_EQ(a.result, code(ErrorCode::not_owner));
  EXPECT_EQ(r->task().motion().queued(), 0u);
  const std::vector<ElementAck> acks = owner.send_frames({mine.tail});
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].result, kOk);
  EXPECT_EQ(plane(r->task().motion().queue_end_mm()), plane(mine.end_mm)) << "the owner's element, not host 2's";
}

TEST(CanNodeSegments, HeartbeatAndProgramStatusReportTheFreeSlotsAndProgress) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  ProgramHost host(*r);
  for (int k = 0; k < 5; ++k) ASSERT_EQ(host.send(fw::motion::dwell_for(0.01)).at(0).result, kOk);
  host.others.clear();
  // PROGRAM_STATUS on request, from any host (no ownership needed).
  r->port.send(with_tag(command(kRigNode, CommandCode::program_status), 0x31));
  r->service();
  const std::vector<ElementAck> acks = host.collect();
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].result, kOk);
  const std::vector<hal::CanFrame> status = only(host.others, MessageId::program_status);
  ASSERT_EQ(status.size(), 1u);
  EXPECT_EQ(raw_of(status[0], MessageId::program_status, "state"), static_cast<std::uint32_t>(can::ProgramState::running));
  EXPECT_EQ(raw_of(status[0], MessageId::program_status, "free_slots"), fw::motion::kSegmentQueueCapacity - 5);
  EXPECT_EQ(raw_of(status[0], MessageId::program_status, "segment"), 1u);
  EXPECT_EQ(raw_of(status[0], MessageId::program_status, "feed_override"), 100u);
  // HEARTBEAT: turned on, its free_slots byte is the queue's.
  ASSERT_EQ(r->result(param_request(kRigNode, can::ParamOp::set, param_id("tlm.heartbeat_ms"), 1)), kOk);
  r->step();
  const std::vector<hal::CanFrame> hb = only(r->port.drain(), MessageId::heartbeat);
  ASSERT_FALSE(hb.empty());
  EXPECT_EQ(raw_of(hb.back(), MessageId::heartbeat, "free_slots"), r->task().motion().free_slots());
  EXPECT_LT(r->task().motion().free_slots(), fw::motion::kSegmentQueueCapacity);
}

TEST(CanNodeSegments, ProgramCommandsHoldResumeOverrideAndEnd) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  EXPECT_EQ(ack_result(*r, command(kRigNode, CommandCode::feed_hold)), code(ErrorCode::busy)) << "no program runs";
  ProgramHost host(*r);
  ASSERT_EQ(host.send(fw::motion::line_to(offset(host.at_mm(), 20.0, 0.0), 10.0)).at(0).result, kOk);
  const std::vector<hal::CanFrame> out = r->request(command(kRigNode, CommandCode::feed_override, 0, 151));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(raw_of(out[0], MessageId::command_ack, "result"), code(ErrorCode::out_of_range));
  EXPECT_EQ(raw_of(out[0], MessageId::command_ack, "detail"), fld::index_of(fld::kCommandMsg, fld::kCommandArg));
  EXPECT_EQ(ack_result(*r, command(kRigNode, CommandCode::feed_override, 0, 50)), kOk);
  EXPECT_DOUBLE_EQ(r->task().motion().feed_override(), 0.5);
  EXPECT_EQ(ack_result(*r, command(kRigNode, CommandCode::feed_hold)), kOk);
  for (int k = 0; k < 400; ++k) r->step();
  EXPECT_EQ(r->task().motion().state(), fw::motion::MotionState::holding);
  EXPECT_EQ(r->node->program().state(), can::ProgramState::holding);
  EXPECT_EQ(ack_result(*r, command(kRigNode, CommandCode::feed_resume)), kOk);
  EXPECT_EQ(ack_result(*r, command(kRigNode, CommandCode::end_program)), kOk);
  ASSERT_TRUE(r->run_until(fw::MotionState::holding, 10000));
  for (int k = 0; k < 2; ++k) r->step();
  EXPECT_EQ(r->node->program().state(), can::ProgramState::done);
  EXPECT_EQ(ack_result(*r, command(kRigNode, CommandCode::abort_program)), kOk) << "nothing left to abort";
}

}  // namespace
}  // namespace tnv::test
