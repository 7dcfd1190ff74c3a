// Tick-path discipline (design notes "The tick"): over 10,000 ticks of the
// full HIL rig the tick allocates nothing, throws nothing and makes no
// system call (so it can neither block on a lock, sleep, log nor do I/O).
//  - allocations: global operator new/delete are replaced in this binary
//    and count while armed;
//  - exceptions: tick() is noexcept (checked at compile time);
//  - system calls: a forked child runs the ticks under a seccomp filter that
//    kills the process on any system call except exit.
#include <gtest/gtest.h>
#include <linux/filter.h>
#include <linux/seccomp.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

#include "emulator/scenario_file.hpp"
#include "firmware/can/can_node.hpp"
#include "firmware/control/speed_observer_design.hpp"
#include "tests/firmware/can/can_test_doubles.hpp"
#include "tests/hil/hil_rig.hpp"

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};

void* counted_alloc(std::size_t n) {
  if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* counted_aligned_alloc(std::size_t n, std::align_val_t a) {
  if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1, std::memory_order_relaxed);
  const auto align = static_cast<std::size_t>(a);
  if (void* p = std::aligned_alloc(align, ((n + align - 1) / align) * align)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t n) { return counted_alloc(n); }
void* operator new[](std::size_t n) { return counted_alloc(n); }
void* operator new(std::size_t n, std::align_val_t a) { return counted_aligned_alloc(n, a); }
void* operator new[](std::size_t n, std::align_val_t a) { return counted_aligned_alloc(n, a); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

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
    g_allocations = 0;
    g_counting = true;
    rig.task.tick();
    g_counting = false;
    allocations += g_allocations;
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
  g_allocations = 0;
  g_counting = true;
  const fw::CommandStatus configured = rig->task.configure_shaper(hal::Axis::x, spec);
  const fw::CommandStatus enabled = rig->task.enable_shaper(hal::Axis::x, true);
  const fw::CommandStatus held = rig->task.hold_position();
  g_counting = false;
  ASSERT_EQ(configured, fw::CommandStatus::ok);
  ASSERT_EQ(enabled, fw::CommandStatus::ok);
  ASSERT_EQ(held, fw::CommandStatus::ok);
  EXPECT_EQ(g_allocations, 0) << "heap allocations while designing the shaper";
  long allocations = 0;
  for (int i = 0; i < kTicks; ++i) {
    rig->machine.advance_to_next_tick();
    g_allocations = 0;
    g_counting = true;
    rig->task.jog(hal::Axis::x, (i / 500) % 2 == 0 ? 20.0 : -20.0);
    rig->task.tick();
    g_counting = false;
    allocations += g_allocations;
  }
  EXPECT_EQ(allocations, 0) << "heap allocations inside the shaped tick";
  EXPECT_TRUE(rig->task.shaper(hal::Axis::x).shaping());
  EXPECT_EQ(rig->task.state(), fw::MotionState::moving) << "fault: " << fw::to_string(rig->task.fault().reason);
}

TEST(TickDiscipline, TheCounterSeesAnAllocationWhenThereIsOne) {
  // Guards the guard: the replaced operator new really counts.
  g_allocations = 0;
  g_counting = true;
  auto* p = new std::vector<int>(100);
  g_counting = false;
  delete p;
  EXPECT_GE(g_allocations.load(), 1);
}

// Runs body() in a forked child under a seccomp filter that allows only
// exit/exit_group. Returns the child's exit code, or -signal if killed,
// or 77 if seccomp could not be installed.
template <typename Body>
int run_without_syscalls(Body body) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    struct sock_filter filter[] = {
        BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(struct seccomp_data, nr)),
        BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, __NR_exit_group, 0, 1),
        BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ALLOW),
        BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, __NR_exit, 0, 1),
        BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ALLOW),
        BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_KILL_PROCESS),
    };
    struct sock_fprog prog = {static_cast<unsigned short>(sizeof filter / sizeof filter[0]), filter};
    if (::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) ::_exit(77);
    if (::prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &prog) != 0) ::_exit(77);
    const int code = body();
    ::syscall(SYS_exit_group, code);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return WIFSIGNALED(status) ? -WTERMSIG(status) : -1000;
}

TEST(TickDiscipline, TheTickMakesNoSystemCallOver10000Ticks) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "the sanitizer runtime makes its own system calls; proven in the plain build";
#endif
  auto rig = running_rig();
  ASSERT_TRUE(rig && rig->init_ok);
  const int result = run_without_syscalls([&] {
    for (int i = 0; i < kTicks; ++i) {
      rig->machine.advance_to_next_tick();
      rig->task.tick();
    }
    return rig->task.state() == fw::MotionState::moving ? 0 : 3;
  });
  if (result == 77) GTEST_SKIP() << "seccomp is not available on this kernel";
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
  const int result = run_without_syscalls([&] {
    for (int i = 0; i < 2000; ++i) {
      rig->machine.advance_to_next_tick();
      rig->task.tick();
    }
    return rig->task.state() == fw::MotionState::moving ? 0 : 3;
  });
  if (result != 77) {  // 77: seccomp not available on this kernel
    EXPECT_EQ(result, 0) << "the observer tick made a system call (or the circle stopped)";
  }
#endif
}

TEST(TickDiscipline, TheSeccompGuardCatchesASystemCall) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "sanitizer build";
#endif
  const int result = run_without_syscalls([] { return ::getppid() > 0 ? 0 : 1; });
  if (result == 77) GTEST_SKIP() << "seccomp is not available on this kernel";
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
    s.telemetry = {10, 1, 1, 1, 1, 1};
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
    g_allocations = 0;
    g_counting = true;
    b.node->service();
    g_counting = false;
    allocations += g_allocations;
    for (const hal::CanFrame& f : b.port.drain()) {  // the host's side allocates, outside the count
      data_frames += test::is(f, fw::can::MessageId::capture_data) ? 1 : 0;
      replies += test::is(f, fw::can::MessageId::param_reply) ? 1 : 0;
    }
  }
  EXPECT_EQ(allocations, 0) << "heap allocations inside service()";
  EXPECT_EQ(b.rig->task.sliding_params(hal::Axis::x).gamma, static_cast<double>(0.3f)) << "the set was applied";
  EXPECT_EQ(b.rig->task.pid_params(hal::Axis::x).kp, 500.0) << "the commit was applied";
  EXPECT_EQ(replies, 4u);
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
  const int result = run_without_syscalls([&] {
    for (int k = 0; k < 400; ++k) {
      b.host(k);  // the fake port's rings: no allocation, no system call
      b.rig->machine.advance_to_next_tick();
      b.rig->task.tick();
      b.node->service();
      b.port.from_node.clear();
    }
    return b.rig->task.pid_params(hal::Axis::x).kp == 500.0 ? 0 : 3;
  });
  if (result == 77) GTEST_SKIP() << "seccomp is not available on this kernel";
  EXPECT_EQ(result, 0) << (result < 0 ? "killed by signal " + std::to_string(-result) + ": service() made a system call"
                                      : "the commit did not apply inside the child");
}

}  // namespace
}  // namespace tnv::hil
