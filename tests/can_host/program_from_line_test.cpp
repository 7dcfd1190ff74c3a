// Run from line over the virtual bus to the emulated node (`tnvctl run
// --from-line`): from where the table stands the interpreter's approach
// and the rest of the program run, and the run ends where the full run
// ends.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "tools/can/program_run.hpp"
#include "tools/can_emu/emulated_bus.hpp"

namespace tnv {
namespace {

using can_host::StreamResult;

const std::string kFromLineProgram =
    "G21 G91 G17 F600\n"  // 1
    "G1 X3\n"             // 2
    "G1 Y3\n"             // 3
    "G3 X-2 Y2 I-2 J0\n"  // 4
    "G1 X4 Y-1\n"         // 5
    "M2\n";

fw::motion::PlanePoint end_of_run(const std::string& name, int from_line) {
  can_host::EmulatedNodeOptions o;
  o.storage_path = (std::filesystem::temp_directory_path() / ("tnv_from_" + std::to_string(::getpid()) + name)).string();
  std::string error;
  auto bus = can_host::EmulatedBus::create(o, error);
  EXPECT_TRUE(bus) << error;
  if (!bus) return {};
  can_host::NodeClient client(*bus, 1);
  can_host::ProgramRunOptions ro;
  if (from_line > 0) {
    ro.canon.from_line = gcode::RunFromLine{};
    ro.canon.from_line->line = from_line;
  }
  const can_host::ProgramRunResult r = can_host::run_gcode(client, kFromLineProgram, ro);
  EXPECT_EQ(r.stream.end, StreamResult::End::done) << r.stream.message;
  if (from_line > 0) {
    for (const fw::motion::Segment& s : r.program.segments) {
      EXPECT_GE(s.tag, static_cast<std::uint32_t>(from_line));
    }
  }
  const fw::TickRecord& rec = bus->rig().task.last_record();
  std::filesystem::remove(o.storage_path);
  return {rec.axis[0].reference_mm, rec.axis[1].reference_mm};
}

TEST(ProgramFromLine, ARunFromLineEndsWhereTheFullRunEnds) {
  const fw::motion::PlanePoint full = end_of_run("full", 0);
  for (const int line : {3, 4, 5}) {
    const fw::motion::PlanePoint part = end_of_run("line" + std::to_string(line), line);
    EXPECT_LT(std::hypot(full[0] - part[0], full[1] - part[1]), 1e-6)
        << "from line " << line << ": (" << part[0] << ", " << part[1] << ") against the full run's (" << full[0]
        << ", " << full[1] << ")";
  }
}

// A run from line after a tool change takes the tool in the spindle from the
// node when the node knows it (a confirmed M6 on it): no second change. A
// node that does not know it (just started) gets the change at the start,
// as with no tool: the operator says which tool is in.
TEST(ProgramFromLine, TheToolInTheSpindleIsTheNodesWhenItKnowsIt) {
  const std::string text = "G21 G91 G17 F600\nT2 M6\nG1 X3\nG1 Y3\nM2\n";
  can_host::EmulatedNodeOptions o;
  o.storage_path = (std::filesystem::temp_directory_path() / ("tnv_from_" + std::to_string(::getpid()) + "tool")).string();
  std::string error;
  auto bus = can_host::EmulatedBus::create(o, error);
  ASSERT_TRUE(bus) << error;
  can_host::NodeClient client(*bus, 1);
  can_host::ProgramRunOptions ro;
  ASSERT_TRUE(ro.canon.tools.load_text("T2 P2 Z0\n", error)) << error;
  ro.resume = [](const can_host::StreamPause&, can_host::Micros) { return true; };
  ro.canon.from_line = gcode::RunFromLine{};
  ro.canon.from_line->line = 4;
  ro.tool_from_node = true;
  // What `tnvctl run` checks its pauses with before sending: none while the node knows none.
  EXPECT_EQ(can_host::with_node_tool(client, ro).canon.from_line->tool_in_spindle, 0);

  const can_host::ProgramRunResult unknown = can_host::run_gcode(client, text, ro);
  ASSERT_EQ(unknown.stream.end, StreamResult::End::done) << unknown.stream.message;
  ASSERT_EQ(unknown.stream.pauses.size(), 1u) << "the node knew no tool: the start changes to T2";
  ASSERT_TRUE(unknown.stream.pauses[0].why);
  EXPECT_EQ(unknown.stream.pauses[0].why->tool, 2);
  ASSERT_EQ(client.program_tool(), (can_host::ProgramTool{true, 2}));

  const can_host::ProgramRunResult known = can_host::run_gcode(client, text, ro);
  ASSERT_EQ(known.stream.end, StreamResult::End::done) << known.stream.message;
  EXPECT_TRUE(known.stream.pauses.empty()) << "T2 is in, as the node knows: no change";
  const can_host::ProgramRunOptions asked = can_host::with_node_tool(client, ro);
  EXPECT_EQ(asked.canon.from_line->tool_in_spindle, 2);
  EXPECT_FALSE(asked.tool_from_node) << "asked once: the run uses the same answer";

  ro.tool_from_node = false;  // the operator's word (--tool-in-spindle 0) stands over the node's
  const can_host::ProgramRunResult told = can_host::run_gcode(client, text, ro);
  ASSERT_EQ(told.stream.end, StreamResult::End::done) << told.stream.message;
  EXPECT_EQ(told.stream.pauses.size(), 1u);
  std::filesystem::remove(o.storage_path);
}

}  // namespace
}  // namespace tnv
