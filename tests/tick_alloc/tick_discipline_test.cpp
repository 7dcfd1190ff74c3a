// Tick-path discipline (design notes "The tick"): over 10,000 ticks of the
// full HIL rig the tick allocates nothing, throws nothing and makes no
// system call (so it can neither block on a lock, sleep, log nor do I/O).
//  - allocations: the allocation guard (alloc_guard.hpp) counts every heap
//    call, operator new/delete and the malloc family alike;
//  - exceptions: tick() is noexcept (checked at compile time);
//  - system calls: a forked child runs the ticks under a seccomp filter that
//    kills the process on any system call except exit (seccomp_guard.hpp).
// tick_sources_test.cpp and can_messages_discipline_test.cpp run every
// controller, motion source, fault path and CAN message under both.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

#include "emulator/scenario_file.hpp"
#include "firmware/can/can_node.hpp"
#include "firmware/control/speed_observer_design.hpp"
#include "firmware/motion/motion_interpolator.hpp"
#include "tests/firmware/can/can_test_doubles.hpp"
#include "tests/hil/hil_rig.hpp"
#include "tests/tick_alloc/alloc_guard.hpp"
#include "tests/tick_alloc/seccomp_guard.hpp"

namespace tnv::hil {
namespace {

constexpr int kTicks = 10'000;

static_assert(noexcept(std::declval<fw::TickTask&>().tick()), "the tick must be noexcept");

// Cutting on, circle running: every branch of a normal tick is exercised.
std::unique_ptr<test::HilRig> running_rig() {
  auto rig = std::make_unique<test::HilRig>(*emu::builtin_scenario("cut-1200"));
  for (int i = 0; i < 3; ++i) rig->tick();
  if (rig->task.start_circle(circle_spec_for(rig->scenario)) != fw::CommandStatus::ok) return nullptr;
  for (int i = 0; i < 600; ++i) rig->tick();  // past the dwell, into the motion
  return rig;
}

// Heap allocations counted over `ticks` ticks of the running rig (only
// inside TickTask::tick(), not in the emulator between them).
long allocations_over_ticks(test::HilRig& rig, int ticks) {
  long allocations = 0;
  for (int i = 0; i < ticks; ++i) {
    rig.machine.advance_to_next_tick();
    allocations += test::heap_calls_in([&] { rig.task.tick(); });
  }
  return allocations;
}

TEST(TickDiscipline, TheTickAllocatesNothingOver10000Ticks) {
  auto rig = running_rig();
  ASSERT_TRUE(rig && rig->init_ok);
  ASSERT_EQ(rig->task.state(), fw::MotionState::moving);
  const long allocations = allocations_over_ticks(*rig, kTicks);
  EXPECT_EQ(allocations, 0) << "heap allocations inside the tick";
  EXPECT_EQ(rig->task.state(), fw::MotionState::moving) << "the rig must still be running the circle";
  EXPECT_EQ(rig->task.counters().ticks, static_cast<std::uint64_t>(kTicks + 603));
}

// The input shaper in the reference path (a two-mode ZVDD, 30 Hz x 11 Hz)
// under a live jog stream that reverses every 0.5 s: the shaper commands
// and the ticks alike allocate nothing.
TEST(TickDiscipline, TheShapedJogAllocatesNothingOver10000Ticks) {
  auto rig = std::make_unique<test::HilRig>(*emu::builtin_scenario("flex-30"));
  ASSERT_TRUE(rig->init_ok);
  for (int i = 0; i < 3; ++i) rig->tick();
  const fw::ShaperSpec spec{fw::ShaperType::zvdd, {30.0, 0.02}, {11.0, 0.02}};
  fw::CommandStatus configured{}, enabled{}, held{};
  const long design_allocations = test::heap_calls_in([&] {
    configured = rig->task.configure_shaper(hal::Axis::x, spec);
    enabled = rig->task.enable_shaper(hal::Axis::x, true);
    held = rig->task.hold_position();
  });
  ASSERT_EQ(configured, fw::CommandStatus::ok);
  ASSERT_EQ(enabled, fw::CommandStatus::ok);
  ASSERT_EQ(held, fw::CommandStatus::ok);
  EXPECT_EQ(design_allocations, 0) << "heap allocations while designing the shaper";
  long allocations = 0;
  for (int i = 0; i < kTicks; ++i) {
    rig->machine.advance_to_next_tick();
    allocations += test::heap_calls_in([&] {
      rig->task.jog(hal::Axis::x, (i / 500) % 2 == 0 ? 20.0 : -20.0);
      rig->task.tick();
    });
  }
  EXPECT_EQ(allocations, 0) << "heap allocations inside the shaped tick";
  EXPECT_TRUE(rig->task.shaper(hal::Axis::x).shaping());
  EXPECT_EQ(rig->task.state(), fw::MotionState::moving) << "fault: " << fw::to_string(rig->task.fault().reason);
}

// Guards the guard: a new, a malloc (Eigen's way in) and a calloc all count.
TEST(TickDiscipline, TheGuardSeesANew) {
  std::vector<int>* p = nullptr;
  EXPECT_GE(test::heap_calls_in([&] { p = new std::vector<int>(100); }), 1);
  delete p;
}

// The nothrow form (std::stable_sort's temporary buffer) counts too, and
// its block is freed by the matching delete, also under a sanitizer.
TEST(TickDiscipline, TheGuardSeesANothrowNew) {
  int* p = nullptr;
  EXPECT_GE(test::heap_calls_in([&] { p = new (std::nothrow) int[100]; }), 1);
  ASSERT_NE(p, nullptr);
  delete[] p;
  std::vector<int> values(1000);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<int>((i * 7919) % 1000);
  std::stable_sort(values.begin(), values.end());
  EXPECT_TRUE(std::is_sorted(values.begin(), values.end()));
}

TEST(TickDiscipline, TheGuardSeesAMallocAndACalloc) {
  if (!test::kMallocCounted) GTEST_SKIP() << "the sanitizer owns malloc; proven in the plain build";
  void* volatile p = nullptr;
  EXPECT_GE(test::heap_calls_in([&] { p = std::malloc(64); }), 1);
  EXPECT_GE(test::heap_calls_in([&] { std::free(p); }), 1);
  EXPECT_GE(test::heap_calls_in([&] { p = std::calloc(8, 8); }), 1);
  EXPECT_GE(test::heap_calls_in([&] { p = std::realloc(p, 256); }), 1);
  std::free(p);
  void* q = nullptr;
  EXPECT_GE(test::heap_calls_in([&] { (void)posix_memalign(&q, 64, 128); }), 1);
  std::free(q);
  EXPECT_GE(test::heap_calls_in([&] { q = std::aligned_alloc(64, 128); }), 1);
  std::free(q);
}

TEST(TickDiscipline, TheTickMakesNoSystemCallOver10000Ticks) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "the sanitizer runtime makes its own system calls; proven in the plain build";
#endif
  auto rig = running_rig();
  ASSERT_TRUE(rig && rig->init_ok);
  const int result = test::run_without_syscalls([&] {
    for (int i = 0; i < kTicks; ++i) {
      rig->machine.advance_to_next_tick();
      rig->task.tick();
    }
    return rig->task.state() == fw::MotionState::moving ? 0 : 3;
  });
  if (result == test::kSeccompUnavailable) GTEST_SKIP() << "seccomp is not available on this kernel";
  EXPECT_EQ(result, 0) << (result < 0 ? "killed by signal " + std::to_string(-result) + ": the tick made a system call"
                                      : "the circle stopped running inside the child");
}

// The speed observer (issue 7) switched on for both axes, with gains from
// the Kalman rule on the paper's models: the circle's ticks still allocate
// nothing.
TEST(TickDiscipline, TheObserverTickAllocatesNothingOver10000Ticks) {
  fw::FirmwareConfig config = fw::default_firmware_config();
  for (auto& axis : config.axis) {
    const fw::ObserverDesign d = fw::steady_state_kalman_gain(axis.model, {0.5, 2.0, axis.count_mm});
    ASSERT_TRUE(d.ok);
    axis.observer = d.params;
    axis.observer.enabled = true;
    axis.observer.use_position = true;
  }
  auto rig = std::make_unique<test::HilRig>(*emu::builtin_scenario("cut-1200"), config);
  ASSERT_TRUE(rig->init_ok);
  ASSERT_TRUE(rig->task.config().axis[0].observer.enabled);
  for (int i = 0; i < 3; ++i) rig->tick();
  ASSERT_EQ(rig->task.start_circle(circle_spec_for(rig->scenario)), fw::CommandStatus::ok);
  for (int i = 0; i < 600; ++i) rig->tick();
  const long allocations = allocations_over_ticks(*rig, kTicks);
  EXPECT_EQ(allocations, 0) << "heap allocations inside the tick with the observer on";
  EXPECT_EQ(rig->task.state(), fw::MotionState::moving) << "fault: " << fw::to_string(rig->task.fault().reason);
#if !defined(__SANITIZE_ADDRESS__)
  const int result = test::run_without_syscalls([&] {
    for (int i = 0; i < 2000; ++i) {
      rig->machine.advance_to_next_tick();
      rig->task.tick();
    }
    return rig->task.state() == fw::MotionState::moving ? 0 : 3;
  });
  if (result != test::kSeccompUnavailable) {
    EXPECT_EQ(result, 0) << "the observer tick made a system call (or the circle stopped)";
  }
#endif
}

TEST(TickDiscipline, TheSeccompGuardCatchesASystemCall) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "sanitizer build";
#endif
  const int result = test::run_without_syscalls([] { return ::getppid() > 0 ? 0 : 1; });
  if (result == test::kSeccompUnavailable) GTEST_SKIP() << "seccomp is not available on this kernel";
  EXPECT_EQ(result, -SIGSYS) << "a getppid() under the filter must kill the child";
}

// The CAN service between ticks (firmware/can/can_node.hpp): while a
// circle runs with telemetry on, service() calls that handle a parameter
// set, a staged commit, a capture arm and a segmented upload allocate
// nothing and make no system call.
struct CanBench {
  explicit CanBench(std::unique_ptr<test::HilRig> r) : rig(std::move(r)) {
    fw::can::NodeSettings s = fw::can::default_node_settings();
    s.firmware = rig->task.config();
    s.telemetry = {10, 1, 1, 1, 1, 1, 1};
    s.capture.trigger = fw::can::CaptureTrigger::immediate;
    node = std::make_unique<fw::can::CanNode>(rig->task, port, storage, s);
  }
  // Frames the host sends during the measured run: at step k.
  void host(int k) {
    using fw::can::ParamOp;
    const std::uint16_t gamma = fw::can::find_param("x.sliding.gamma")->id;
    const std::uint16_t kp = fw::can::find_param("x.pid.kp")->id;
    if (k == 5) port.send(test::command(1, fw::can::CommandCode::take_ownership));  // set and commit need it
    if (k == 10) port.send(test::capture_control(1, fw::can::CaptureOp::arm));
    if (k == 100) port.send(test::capture_control(1, fw::can::CaptureOp::abort));
    if (k == 200) port.send(test::param_request(1, ParamOp::set, gamma, test::f32_raw(0.3f)));
    if (k == 201) port.send(test::param_request(1, ParamOp::stage, kp, test::f32_raw(500.0f)));
    if (k == 202) port.send(test::param_request(1, ParamOp::commit, 0));
    if (k == 300) port.send(test::capture_control(1, fw::can::CaptureOp::upload, 255, 0));
    if (k == 301) port.send(test::param_request(1, ParamOp::get, gamma));
    // The force loop's reference is live: a new f* reaches the task between two ticks.
    if (k == 302) port.send(test::param_request(1, ParamOp::set, fw::can::find_param("arsc.force_ref_n")->id,
                                                 test::f32_raw(120.0f)));
  }
  std::unique_ptr<test::HilRig> rig;
  test::FakeCanPort port;
  test::MemoryStorage storage;
  std::unique_ptr<fw::can::CanNode> node;
};

static_assert(noexcept(std::declval<fw::can::CanNode&>().service()), "service() must be noexcept");

TEST(TickDiscipline, TheCanServiceAllocatesNothingForAParamSetACommitAndACaptureUpload) {
  auto rig = running_rig();
  ASSERT_TRUE(rig && rig->init_ok);
  CanBench b(std::move(rig));
  long allocations = 0;
  std::size_t data_frames = 0;
  std::size_t replies = 0;
  for (int k = 0; k < 400; ++k) {
    b.host(k);
    b.rig->machine.advance_to_next_tick();
    b.rig->task.tick();
    allocations += test::heap_calls_in([&] { b.node->service(); });
    for (const hal::CanFrame& f : b.port.drain()) {  // the host's side allocates, outside the count
      data_frames += test::is(f, fw::can::MessageId::capture_data) ? 1 : 0;
      replies += test::is(f, fw::can::MessageId::param_reply) ? 1 : 0;
    }
  }
  EXPECT_EQ(allocations, 0) << "heap allocations inside service()";
  EXPECT_EQ(b.rig->task.sliding_params(hal::Axis::x).gamma, static_cast<double>(0.3f)) << "the set was applied";
  EXPECT_EQ(b.rig->task.pid_params(hal::Axis::x).kp, 500.0) << "the commit was applied";
  EXPECT_EQ(b.rig->task.config().arsc.force_ref_n, static_cast<double>(120.0f)) << "the live f* was applied";
  EXPECT_EQ(replies, 5u);
  EXPECT_EQ(data_frames, 255u) << "the whole upload block went out";
  EXPECT_EQ(b.rig->task.state(), fw::MotionState::moving);
}

TEST(TickDiscipline, TheCanServiceMakesNoSystemCall) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "the sanitizer runtime makes its own system calls; proven in the plain build";
#endif
  auto rig = running_rig();
  ASSERT_TRUE(rig && rig->init_ok);
  CanBench b(std::move(rig));
  const int result = test::run_without_syscalls([&] {
    for (int k = 0; k < 400; ++k) {
      b.host(k);  // the fake port's rings: no allocation, no system call
      b.rig->machine.advance_to_next_tick();
      b.rig->task.tick();
      b.node->service();
      b.port.from_node.clear();
    }
    return b.rig->task.pid_params(hal::Axis::x).kp == 500.0 ? 0 : 3;
  });
  if (result == test::kSeccompUnavailable) GTEST_SKIP() << "seccomp is not available on this kernel";
  EXPECT_EQ(result, 0) << (result < 0 ? "killed by signal " + std::to_string(-result) + ": service() made a system call"
                                      : "the commit did not apply inside the child");
}

// The motion core (firmware/motion/): pushing segments and ticking through
// lines, corners and arcs allocates nothing and makes no system call.
TEST(TickDiscipline, TheMotionCoreAllocatesNothingAndMakesNoSystemCall) {
  using namespace fw::motion;
  std::vector<Segment> program;
  for (int i = 1; i <= 200; ++i) program.push_back(line_to({0.5 * i, (i % 2) * 0.5}, 20.0));
  program.push_back(arc_to(false, {100.0, 0.0}, {100.0, 5.0}, 20.0));
  program.push_back(dwell_for(0.01));
  const auto run = [&program](MotionInterpolator& m, int ticks) {
    std::size_t next = 0;
    for (int k = 0; k < ticks; ++k) {
      while (next < program.size() && m.free_slots() > 0) (void)m.push(program[next++]);
      if (k == ticks / 2) (void)m.set_feed_override(1.2);
      (void)m.tick();
    }
    return m.stats().segments_accepted == program.size() ? 0 : 3;
  };
  MotionInterpolator counted;
  ASSERT_STREQ(counted.configure({}, {0.0, 0.0}), "");
  int counted_result = -1;
  const long heap_calls = test::heap_calls_in([&] { counted_result = run(counted, 20000); });
  EXPECT_EQ(counted_result, 0) << "the program did not run through";
  EXPECT_EQ(heap_calls, 0) << "heap allocations in the motion core";

  MotionInterpolator sealed;
  ASSERT_STREQ(sealed.configure({}, {0.0, 0.0}), "");
  const int result = test::run_without_syscalls([&] { return run(sealed, 20000); });
  if (result == test::kSeccompUnavailable) GTEST_SKIP() << "seccomp is not available on this kernel";
  EXPECT_EQ(result, 0) << (result < 0 ? "killed by signal " + std::to_string(-result) + ": the motion core made a system call"
                                      : "the program did not run through");
}

}  // namespace
}  // namespace tnv::hil
