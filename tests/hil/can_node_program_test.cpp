// A program streamed to the node on the emulated TNV-40: a host that pauses
// makes the queue run dry (an underrun: at rest on the path, counted once,
// no fault) and the program then runs on to its end exactly on the path; a
// stop mid-program brakes on the path and drops the rest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/hil/program_frames.hpp"
#include "tools/gcode/path_distance.hpp"

namespace tnv::test {
namespace {

namespace can = fw::can;
using can::CommandCode;
using fw::motion::PlanePoint;

struct Trace {
  std::vector<PlanePoint> reference_mm;
  void record(const fw::TickTask& task) {
    reference_mm.push_back({task.last_record().axis[0].reference_mm, task.last_record().axis[1].reference_mm});
  }
  double deviation_max_mm(const gcode::GcodeProgram& program) const {
    const gcode::ProgrammedPath path(program.geometry);
    double worst = 0.0;
    for (const PlanePoint& p : reference_mm) worst = std::max(worst, path.distance_mm(p));
    return worst;
  }
  // Largest |second difference| / dt^2 of the reference over the axis' acceleration limit.
  double accel_ratio_max(const fw::motion::MotionLimits& limits) const {
    double worst = 0.0;
    for (std::size_t k = 2; k < reference_mm.size(); ++k)
      for (std::size_t i = 0; i < 2; ++i)
        worst = std::max(worst, std::fabs(reference_mm[k][i] - 2 * reference_mm[k - 1][i] + reference_mm[k - 2][i]) /
                                    1e-6 / limits.axis[i].accel_mm_s2);
    return worst;
  }
};


bool send_all(ProgramHost& host, const gcode::GcodeProgram& p, std::size_t from, std::size_t to) {
  for (std::size_t k = from; k < to; ++k) {
    const std::vector<ElementAck> acks = host.send(p.segments[k]);
    if (acks.size() != 1 || acks[0].result != kOk) return false;
  }
  return true;
}

TEST(CanNodeProgram, AnUnderrunWaitsOnThePathIsCountedOnceAndTheProgramResumesToItsEnd) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  const gcode::GcodeProgram program = relative_program(*r, zigzag_arcs_text());
  ASSERT_EQ(program.segments.size(), 32u);
  ProgramHost host(*r);
  Trace trace;
  ASSERT_TRUE(send_all(host, program, 0, 10));
  // The host pauses: the queue runs dry and the table waits at rest at the end of element 10.
  int ticks = 0;
  while (r->task().motion().state() != fw::motion::MotionState::starved && ticks++ < 20000) {
    r->step();
    trace.record(r->task());
  }
  ASSERT_EQ(r->task().motion().state(), fw::motion::MotionState::starved) << "the queue never ran dry";
  for (int k = 0; k < 300; ++k) {
    r->step();
    trace.record(r->task());
  }
  EXPECT_EQ(r->task().state(), fw::MotionState::moving) << "an underrun is not the program's end";
  EXPECT_FALSE(r->task().fault().active());
  EXPECT_EQ(r->node->program().state(), can::ProgramState::starved);
  EXPECT_EQ(r->node->program().underruns(r->task()), 1u);
  const PlanePoint waiting = trace.reference_mm.back();
  EXPECT_LT(std::hypot(waiting[0] - host.at_mm()[0], waiting[1] - host.at_mm()[1]), 1e-6)
      << "the reference waits at the end of the last element received";

  ASSERT_TRUE(send_all(host, program, 10, program.segments.size()));
  ASSERT_EQ(ack_result(*r, command(kRigNode, CommandCode::end_program)), kOk);
  for (ticks = 0; r->task().state() == fw::MotionState::moving && ticks < 40000; ++ticks) {
    r->step();
    trace.record(r->task());
  }
  for (int k = 0; k < 3; ++k) r->step();
  EXPECT_EQ(r->node->program().state(), can::ProgramState::done);
  EXPECT_EQ(r->node->program().underruns(r->task()), 1u) << "the end after end_program is no underrun";
  EXPECT_FALSE(r->task().fault().active());
  const double deviation_um = trace.deviation_max_mm(program) * 1e3;
  std::printf("[program] underrun run: path deviation max %.3f um over %zu ticks\n", deviation_um, trace.reference_mm.size());
  EXPECT_LE(deviation_um, r->task().config().path_tolerance_mm * 1e3) << "the reference left the programmed path";
  const PlanePoint end = trace.reference_mm.back();
  EXPECT_LT(std::hypot(end[0] - program.geometry.back().end_mm[0], end[1] - program.geometry.back().end_mm[1]), 1e-4)
      << "the program ends on its last point (to the wire's 0.1 um)";
  EXPECT_LE(trace.accel_ratio_max(r->task().motion().limits()), 1.0 + 1e-6);
}

TEST(CanNodeProgram, AStopMidProgramBrakesOnThePathAndDropsTheRest) {
  for (const CommandCode stop : {CommandCode::stop, CommandCode::abort_program}) {
    SCOPED_TRACE(can::to_string(stop));
    auto r = holding_rig();
    ASSERT_TRUE(r);
    const gcode::GcodeProgram program = relative_program(*r, zigzag_arcs_text());
    ProgramHost host(*r);
    ASSERT_TRUE(send_all(host, program, 0, program.segments.size()));
    ASSERT_EQ(ack_result(*r, command(kRigNode, CommandCode::end_program)), kOk);
    Trace trace;
    for (int k = 0; k < 3000; ++k) {
      r->step();
      trace.record(r->task());
    }
    ASSERT_EQ(r->node->program().state(), can::ProgramState::running);
    ASSERT_EQ(ack_result(*r, command(kRigNode, stop)), kOk);
    int ticks = 0;
    for (; r->task().state() == fw::MotionState::moving && ticks < 5000; ++ticks) {
      r->step();
      trace.record(r->task());
    }
    for (int k = 0; k < 3; ++k) r->step();
    EXPECT_EQ(r->task().state(), fw::MotionState::holding);
    EXPECT_LT(ticks, 1000) << "braking from 10 mm/s takes well under a second";
    EXPECT_EQ(r->node->program().state(), can::ProgramState::aborted);
    EXPECT_EQ(r->task().motion().queued(), 0u) << "the rest of the program is dropped";
    EXPECT_FALSE(r->task().fault().active());
    EXPECT_LE(trace.deviation_max_mm(program) * 1e3, r->task().config().path_tolerance_mm * 1e3);
    EXPECT_LE(trace.accel_ratio_max(r->task().motion().limits()), 1.0 + 1e-6);
    const PlanePoint rest = trace.reference_mm.back();
    EXPECT_GT(std::hypot(rest[0] - program.geometry.back().end_mm[0], rest[1] - program.geometry.back().end_mm[1]), 1.0)
        << "stopped mid-program, not at its end";
    // Streaming again starts a new program from where it stands.
    ProgramHost next(*r);
    EXPECT_EQ(next.send(fw::motion::line_to({rest[0] + 1.0, rest[1]}, 5.0)).at(0).result, kOk);
    EXPECT_EQ(r->node->program().state(), can::ProgramState::running);
  }
}

}  // namespace
}  // namespace tnv::test
