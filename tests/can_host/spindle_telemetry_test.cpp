// TLM_SPINDLE on the host: TelemetryView decodes the speeds, flags and stop
// cause; the spindle's state word follows the flags; `tnvctl monitor`'s CSV
// and JSON carry the spindle once the node has sent it and leave it out
// (empty cells, no key) before.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "tools/can/telemetry_csv.hpp"
#include "tools/can/telemetry_json.hpp"
#include "tools/can/telemetry_view.hpp"

namespace tnv {
namespace {

namespace can = fw::can;
namespace f = fw::can::fields;

hal::CanFrame spindle_frame(double target_rpm, double command_rpm, double measured_rpm, std::uint32_t flags,
                            std::uint32_t stop_cause) {
  hal::CanFrame frame = can::make_frame(f::kTlmSpindleMsg, 1);
  can::write(frame, f::kTlmSpindleTarget, target_rpm);
  can::write(frame, f::kTlmSpindleCommand, command_rpm);
  can::write(frame, f::kTlmSpindleMeasured, measured_rpm);
  can::write_raw(frame, f::kTlmSpindleFlags, flags);
  can::write_raw(frame, f::kTlmSpindleStopCause, stop_cause);
  return frame;
}

can_host::SpindleTelemetry decoded(std::uint32_t flags, std::uint32_t stop_cause = 0) {
  can_host::TelemetryView view;
  view.take(spindle_frame(0.0, 0.0, 0.0, flags, stop_cause), can::MessageId::tlm_spindle);
  EXPECT_TRUE(view.spindle.has_value());
  return view.spindle.value_or(can_host::SpindleTelemetry{});
}

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

std::string cell_of(const std::string& header, const std::string& row, const std::string& column) {
  const std::vector<std::string> names = split_csv(header);
  const std::vector<std::string> cells = split_csv(row);
  EXPECT_EQ(names.size(), cells.size()) << row;
  for (std::size_t i = 0; i < names.size() && i < cells.size(); ++i)
    if (names[i] == column) return cells[i];
  ADD_FAILURE() << "no column " << column;
  return "";
}

TEST(SpindleTelemetry, TheFrameIsDecodedIntoTheView) {
  can_host::TelemetryView view;
  EXPECT_FALSE(view.spindle);
  const std::uint32_t flags = can::kSpindleOn | can::kSpindleEnabled | can::kSpindleReverse | can::kSpindleAtSpeed;
  view.take(spindle_frame(-3000.0, -2990.0, -2987.0, flags, static_cast<std::uint32_t>(fw::SpindleStopCause::abort)),
            can::MessageId::tlm_spindle);
  ASSERT_TRUE(view.spindle);
  EXPECT_EQ(view.spindle->target_rpm, -3000.0);
  EXPECT_EQ(view.spindle->command_rpm, -2990.0);
  EXPECT_EQ(view.spindle->measured_rpm, -2987.0);
  EXPECT_TRUE(view.spindle->commanded_on());
  EXPECT_TRUE(view.spindle->at_speed());
  EXPECT_TRUE(view.spindle->reverse());
  EXPECT_FALSE(view.spindle->inhibited());
  EXPECT_EQ(view.spindle->stop_cause, fw::SpindleStopCause::abort);
  EXPECT_EQ(view.frames, 1u);
  EXPECT_FALSE(view.position_mm) << "a spindle frame fills no other slot";
}

TEST(SpindleTelemetry, TheStateWordFollowsTheFlags) {
  EXPECT_STREQ(can_host::spindle_state(decoded(0)), "off");
  EXPECT_STREQ(can_host::spindle_state(decoded(can::kSpindleOn | can::kSpindleEnabled)), "ramping");
  EXPECT_STREQ(can_host::spindle_state(decoded(can::kSpindleOn | can::kSpindleEnabled | can::kSpindleAtSpeed)),
               "at_speed");
  EXPECT_STREQ(can_host::spindle_state(decoded(can::kSpindleEnabled)), "stopping");
  EXPECT_STREQ(can_host::spindle_state(decoded(can::kSpindleInhibited | can::kSpindleEnabled)), "inhibited");
}

TEST(SpindleTelemetry, AStopCauseBeyondTheListReadsAsNone) {
  EXPECT_EQ(decoded(0, static_cast<std::uint32_t>(fw::SpindleStopCause::estop)).stop_cause,
            fw::SpindleStopCause::estop);
  EXPECT_EQ(decoded(0, fw::kSpindleStopCauseCount).stop_cause, fw::SpindleStopCause::none);
}

TEST(SpindleTelemetry, CsvCellsAreEmptyUntilTheSpindleIsHeardThenCarryIt) {
  const std::string header = can_host::telemetry_csv_header();
  can_host::TelemetryView view;
  const std::string before = can_host::telemetry_csv_row(view, 0.0, 0.0);
  EXPECT_EQ(cell_of(header, before, "spindle_state"), "");
  EXPECT_EQ(cell_of(header, before, "spindle_measured_rpm"), "");
  view.take(spindle_frame(1500.0, 1200.0, 1187.0, can::kSpindleOn | can::kSpindleEnabled, 0),
            can::MessageId::tlm_spindle);
  const std::string row = can_host::telemetry_csv_row(view, 0.5, 0.01);
  EXPECT_EQ(cell_of(header, row, "spindle_state"), "ramping");
  EXPECT_EQ(cell_of(header, row, "spindle_target_rpm"), "1500");
  EXPECT_EQ(cell_of(header, row, "spindle_command_rpm"), "1200");
  EXPECT_EQ(cell_of(header, row, "spindle_measured_rpm"), "1187");
  EXPECT_EQ(cell_of(header, row, "spindle_at_speed"), "0");
}

TEST(SpindleTelemetry, JsonHasASpindleObjectOnceHeard) {
  can_host::TelemetryView view;
  EXPECT_FALSE(can_host::telemetry_json(view, 0.0, 0.0).contains("spindle"));
  view.take(spindle_frame(0.0, 0.0, 12.0, can::kSpindleEnabled | can::kSpindleInhibited,
                          static_cast<std::uint32_t>(fw::SpindleStopCause::estop)),
            can::MessageId::tlm_spindle);
  const nlohmann::json j = can_host::telemetry_json(view, 1.0, 0.0);
  ASSERT_TRUE(j.contains("spindle")) << j.dump();
  const nlohmann::json& s = j["spindle"];
  EXPECT_EQ(s["state"], "inhibited");
  EXPECT_EQ(s["measured_rpm"], 12.0);
  EXPECT_EQ(s["command_rpm"], 0.0);
  EXPECT_EQ(s["at_speed"], false);
  EXPECT_EQ(s["inhibited"], true);
  EXPECT_EQ(s["direction"], "forward");
  EXPECT_EQ(s["stop_cause"], "estop");
}

}  // namespace
}  // namespace tnv
