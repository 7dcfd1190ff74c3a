// Between browser tabs, one has control; the others read only and are
// told why, until it gives control back or goes quiet.
#include <gtest/gtest.h>

#include "tools/serve/browser_control.hpp"

namespace tnv::serve {
namespace {

using namespace std::chrono_literals;
const BrowserControl::Clock::time_point t0{};
const std::string kTabA = "tab-a-0123456789";
const std::string kTabB = "tab-b-0123456789";

TEST(BrowserControl, TheSecondTabIsToldAnotherBrowserHasControl) {
  BrowserControl control(10s);
  EXPECT_NE(control.check(kTabA, t0 + 1s), "") << "a tab sent commands without taking control";
  EXPECT_EQ(control.take(kTabA, t0 + 1s), "");
  EXPECT_EQ(control.check(kTabA, t0 + 2s), "");
  EXPECT_EQ(control.take(kTabB, t0 + 2s), kAnotherBrowserHasControl);
  EXPECT_EQ(control.check(kTabB, t0 + 2s), kAnotherBrowserHasControl);
  EXPECT_TRUE(control.holds(kTabA, t0 + 2s));
  EXPECT_FALSE(control.holds(kTabB, t0 + 2s));
}

TEST(BrowserControl, ReleasedControlCanBeTakenByTheOtherTab) {
  BrowserControl control(10s);
  ASSERT_EQ(control.take(kTabA, t0), "");
  EXPECT_FALSE(control.release(kTabB)) << "a tab without control released it";
  EXPECT_EQ(control.take(kTabB, t0 + 1s), kAnotherBrowserHasControl);
  EXPECT_TRUE(control.release(kTabA));
  EXPECT_EQ(control.take(kTabB, t0 + 1s), "");
  EXPECT_EQ(control.check(kTabA, t0 + 1s), kAnotherBrowserHasControl);
}

TEST(BrowserControl, AQuietHolderLosesControlAfterTheDeadmanTime) {
  BrowserControl control(300ms);
  ASSERT_EQ(control.take(kTabA, t0), "");
  EXPECT_TRUE(control.seen(kTabA, t0 + 200ms));  // its heartbeat
  EXPECT_FALSE(control.seen(kTabB, t0 + 200ms)) << "a heartbeat from a tab without control was taken";
  EXPECT_EQ(control.lapse(t0 + 450ms), "") << "lapsed 250 ms after a heartbeat (< 300 ms)";
  EXPECT_EQ(control.take(kTabB, t0 + 450ms), kAnotherBrowserHasControl) << "taken from a holder heard 250 ms ago";
  EXPECT_EQ(control.lapse(t0 + 550ms), kTabA) << "a holder quiet for 350 ms (> 300 ms) still held control";
  EXPECT_EQ(control.lapse(t0 + 560ms), "") << "the lapse was reported twice";
  EXPECT_FALSE(control.seen(kTabA, t0 + 560ms)) << "a late heartbeat gave control back";
  EXPECT_NE(control.check(kTabA, t0 + 560ms), "");
  EXPECT_EQ(control.take(kTabB, t0 + 600ms), "");
}

TEST(BrowserControl, AHolderWhoseStreamClosedLapsesAtOnce) {
  BrowserControl control(10s);
  ASSERT_EQ(control.take(kTabA, t0), "");
  control.gone(kTabB);  // not the holder: nothing
  EXPECT_EQ(control.lapse(t0 + 1s), "");
  control.gone(kTabA);
  EXPECT_EQ(control.lapse(t0 + 1s), kTabA) << "a closed tab kept control for the whole dead-man time";
  EXPECT_EQ(control.take(kTabA, t0 + 2s), "") << "a reloaded tab could not take control again";
  EXPECT_TRUE(control.holds(kTabA, t0 + 2s));
}

TEST(BrowserControl, RefusesAMalformedToken) {
  BrowserControl control(10s);
  EXPECT_NE(control.take("", t0), "");
  EXPECT_NE(control.take("short", t0), "");
  EXPECT_NE(control.take("has space 0123456", t0), "");
  EXPECT_FALSE(control.anyone_holds(t0)) << "a malformed token took control";
}

}  // namespace
}  // namespace tnv::serve
