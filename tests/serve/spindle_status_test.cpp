// The spindle on the tuning page, display only: the scope's spindle_rpm
// channel carries the measured speed from TLM_SPINDLE (NaN, drawn as a gap,
// while the node does not stream it), and /api/status has the spindle once
// tlm.spindle_ms is on and null before.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "tools/serve/telemetry_sample.hpp"
#include "tests/serve/tuning_server_fixture.hpp"
// Last: <resolv.h>, which it includes, defines the macro _res that Eigen's headers use as a name.
#include <httplib.h>

namespace tnv::serve {
namespace {

using namespace tnv::serve::testing;

std::size_t channel_index(const std::string& name) {
  for (std::size_t i = 0; i < kScopeChannels.size(); ++i)
    if (name == kScopeChannels[i].name) return i;
  ADD_FAILURE() << "no scope channel " << name;
  return 0;
}

TEST(SpindleScope, TheMeasuredSpeedIsAChannelAndAGapWhileNotStreamed) {
  const std::size_t k = channel_index("spindle_rpm");
  EXPECT_STREQ(kScopeChannels[k].unit, "rpm");
  can_host::TelemetryView view;
  EXPECT_TRUE(std::isnan(scope_sample(view, 0.0).values[k]));
  namespace f = fw::can::fields;
  hal::CanFrame frame = fw::can::make_frame(f::kTlmSpindleMsg, 1);
  fw::can::write(frame, f::kTlmSpindleTarget, -2000.0);
  fw::can::write(frame, f::kTlmSpindleMeasured, -1994.0);
  fw::can::write_raw(frame, f::kTlmSpindleFlags, fw::can::kSpindleOn | fw::can::kSpindleReverse);
  view.take(frame, fw::can::MessageId::tlm_spindle);
  const ScopeSample s = scope_sample(view, 1.0);
  EXPECT_EQ(s.values[k], -1994.0);
  EXPECT_TRUE(std::isnan(s.values[channel_index("contour_um")])) << "the spindle frame filled another channel";
}

TEST_F(TuningServerTest, TheStatusCarriesTheSpindleOnceTheNodeStreamsIt) {
  const auto status = [&] { return nlohmann::json::parse(http_->Get("/api/status")->body); };
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_TRUE(status()["spindle"].is_null()) << "tlm.spindle_ms is 0 by default: " << status().dump();
  ASSERT_EQ(post("/api/control/take", kTabA)->status, 200);
  const httplib::Result r = post("/api/params/set", kTabA, {{"name", "tlm.spindle_ms"}, {"value", "10"}});
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  nlohmann::json spindle;
  for (int i = 0; i < 200 && spindle.is_null(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    spindle = status()["spindle"];
  }
  ASSERT_FALSE(spindle.is_null()) << "no TLM_SPINDLE in the status within 4 s";
  EXPECT_EQ(spindle["state"], "off") << spindle.dump() << ": nothing started the spindle";
  EXPECT_EQ(spindle["measured_rpm"], 0.0) << spindle.dump();
  EXPECT_EQ(spindle["commanded_on"], false) << spindle.dump();
  EXPECT_EQ(spindle["stop_cause"], "none") << spindle.dump();
}

}  // namespace
}  // namespace tnv::serve
