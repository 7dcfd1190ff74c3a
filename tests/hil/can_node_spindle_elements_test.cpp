// A program's spindle commands as SEGMENT frames on the node: one frame
// each, accepted into the queue in program order; a start above the
// spindle's max_rpm is refused out_of_range naming SEGMENT.x, and the
// queue is left as it was.
#include <gtest/gtest.h>

#include "tests/hil/program_frames.hpp"

namespace tnv::test {
namespace {

namespace can = fw::can;
using can::MessageId;
namespace fld = can::fields;

TEST(CanNodeSpindleElements, OneFrameEachAndAStartAboveMaxRpmIsRefusedNamingX) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  ProgramHost host(*r);
  const double max_rpm = r->task().spindle().params().max_rpm;
  const std::vector<ElementAck> ok =
      host.send(fw::motion::spindle_here(fw::motion::SpindleChange::reverse, 0.5 * max_rpm));
  ASSERT_EQ(ok.size(), 1u);
  EXPECT_EQ(ok[0].result, kOk);
  EXPECT_EQ(ok[0].request, static_cast<std::uint32_t>(MessageId::segment)) << "no SEGMENT_TAIL for a spindle command";
  EXPECT_EQ(r->task().motion().queued(), 1u);
  const std::vector<ElementAck> refused =
      host.send(fw::motion::spindle_here(fw::motion::SpindleChange::forward, 1.5 * max_rpm));
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_EQ(refused[0].result, static_cast<std::uint32_t>(can::ErrorCode::out_of_range));
  EXPECT_EQ(refused[0].detail, fld::index_of(fld::kSegmentMsg, fld::kSegmentX));
  EXPECT_EQ(r->task().motion().queued(), 1u) << "the refusal changed the queue";
  EXPECT_EQ(host.send(fw::motion::spindle_here(fw::motion::SpindleChange::stop, 0.0)).at(0).result, kOk);
  EXPECT_EQ(r->task().motion().queued(), 2u);
}

}  // namespace
}  // namespace tnv::test
