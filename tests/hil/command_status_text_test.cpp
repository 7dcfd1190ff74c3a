// A refused command names the fault that refused it, not only "faulted".
#include "tools/hil/command_status_text.hpp"

#include <gtest/gtest.h>

#include "tests/hil/fault_expect.hpp"
#include "tools/hil/hil_firmware_config.hpp"

namespace tnv::hil {
namespace {

TEST(CommandStatusText, FaultedNamesTheReasonAndTheAxis) {
  const FaultCase c{.name = "encoder_illegal",
                    .fault = {.kind = emu::FaultKind::encoder_illegal, .start_s = 3.0004, .axis = hal::Axis::x}};
  std::unique_ptr<HilRig> rig;
  const FaultObservation o = run_fault_case(test::fault_scenario(), c, fw::ControllerKind::rdvsc, &rig);
  ASSERT_TRUE(o.detected && rig);
  const fw::CommandStatus st = rig->task.start_circle(circle_spec_for(rig->machine.scenario()));
  ASSERT_EQ(st, fw::CommandStatus::faulted);
  EXPECT_EQ(command_status_text(st, rig->task), "faulted (encoder_error, axis x)");
  EXPECT_EQ(command_status_text(fw::CommandStatus::busy, rig->task), "busy") << "only faulted names the fault";
}

}  // namespace
}  // namespace tnv::hil
