// GPIO inputs reach the supervisor through LinuxIoBoard: an e-stop edge on
// a GPIO line puts the outputs safe within one tick (emulated board and
// table, the real driver and firmware, fake GPIO lines).
#include <gtest/gtest.h>

#include "drivers/emulated/emulated_register_bus.hpp"
#include "drivers/fpga/fpga_io_board.hpp"
#include "drivers/linux/linux_io_board.hpp"
#include "emulator/machine.hpp"
#include "emulator/scenario_file.hpp"
#include "firmware/tick/tick_task.hpp"
#include "tools/hil/hil_firmware_config.hpp"

namespace tnv {
namespace {

using drivers::InputLine;

class FakeLines final : public drivers::BoardLines {
 public:
  drivers::InputLevels levels;
  bool read_fails = false;
  int enable_writes = 0;
  bool write_fails = false;
  bool enable_x = true, enable_y = true;
  FakeLines() {
    levels.present[static_cast<std::size_t>(InputLine::estop)] = true;
    levels.present[static_cast<std::size_t>(InputLine::limit_y_neg)] = true;
  }
  bool read_inputs(drivers::InputLevels& out) noexcept override {
    out = levels;
    return !read_fails;
  }
  bool write_enables(bool x, bool y) noexcept override {
    ++enable_writes;
    enable_x = x;
    enable_y = y;
    return !write_fails;
  }
  bool has_tick() const noexcept override { return false; }
  drivers::TickEdge wait_tick(int, std::int64_t&) noexcept override { return drivers::TickEdge::error; }
  void assert_line(InputLine line, bool on) { levels.asserted[static_cast<std::size_t>(line)] = on; }
};

struct Bench {
  emu::Machine machine;
  drivers::EmulatedRegisterBus bus{machine};
  drivers::FpgaIoBoard fpga{bus};
  FakeLines lines;
  drivers::LinuxIoBoard board{fpga, &lines};
  std::unique_ptr<fw::TickTask> task;

  explicit Bench(const emu::Scenario& s) : machine(s) {
    EXPECT_TRUE(fpga.init({}).ok());
    task = std::make_unique<fw::TickTask>(board, hil::firmware_config_for(s, fw::default_firmware_config()));
  }
  void tick() {
    machine.advance_to_next_tick();
    task->tick();
  }
  // Servo on, holding.
  void hold() {
    for (int i = 0; i < 3; ++i) tick();
    ASSERT_EQ(task->hold_position(), fw::CommandStatus::ok);
    for (int i = 0; i < 5; ++i) tick();
    ASSERT_TRUE(machine.board_outputs().enabled[0] && machine.board_outputs().enabled[1]);
    ASSERT_TRUE(lines.enable_x && lines.enable_y) << "the GPIO enables follow the board's";
  }
};

emu::Scenario no_cut() { return *emu::resolve_scenario("no-cut").scenario; }

TEST(LinuxIoBoard, AGpioEstopEdgePutsTheOutputsSafeWithinOneTick) {
  Bench b(no_cut());
  b.hold();
  b.lines.assert_line(InputLine::estop, true);
  b.tick();
  EXPECT_TRUE(b.machine.board_outputs().safe(b.machine.dac_mid_code()))
      << "one tick after the e-stop edge the DACs are mid-scale and the enables off";
  EXPECT_FALSE(b.lines.enable_x || b.lines.enable_y) << "GPIO enables dropped in the same tick";
  EXPECT_EQ(b.task->fault().reason, fw::FaultReason::estop);
}

TEST(LinuxIoBoard, AFailedGpioReadCountsAsEstop) {
  Bench b(no_cut());
  b.hold();
  b.lines.read_fails = true;
  b.tick();
  EXPECT_TRUE(b.machine.board_outputs().safe(b.machine.dac_mid_code()));
  EXPECT_EQ(b.board.gpio_read_failures(), 1u);
}

TEST(LinuxIoBoard, AFailedServoEnableWriteLatchesAFault) {
  Bench b(no_cut());
  b.hold();
  b.lines.write_fails = true;
  b.tick();
  EXPECT_EQ(b.task->state(), fw::MotionState::faulted);
  EXPECT_EQ(b.task->fault().reason, fw::FaultReason::output_write_failed);
  EXPECT_EQ(b.board.gpio_write_failures(), 1u);
  b.tick();  // the next tick's write carries the safe outputs
  EXPECT_TRUE(b.machine.board_outputs().safe(b.machine.dac_mid_code()));
}

TEST(LinuxIoBoard, GpioLimitsJoinTheBoardsInputsAndUnconfiguredLinesAreIgnored) {
  Bench b(no_cut());
  b.tick();
  b.lines.assert_line(InputLine::limit_y_neg, true);
  b.lines.assert_line(InputLine::alarm_x, true);  // not present: ignored
  b.board.read_inputs();
  const hal::DiscreteInputs in = b.board.inputs();
  EXPECT_TRUE(in.limit_negative[1]);
  EXPECT_FALSE(in.servo_alarm[0]);
  EXPECT_FALSE(in.estop);
}

TEST(LinuxIoBoard, ForceSafeOutputsWritesMidScaleAndEnablesOff) {
  Bench b(no_cut());
  b.hold();
  ASSERT_EQ(b.board.force_safe_outputs(), hal::HalStatus::ok);
  EXPECT_TRUE(b.machine.board_outputs().safe(b.machine.dac_mid_code()));
  EXPECT_FALSE(b.lines.enable_x || b.lines.enable_y);
}

}  // namespace
}  // namespace tnv
