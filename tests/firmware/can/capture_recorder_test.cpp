// The capture recorder alone, on synthetic tick records: triggers,
// decimation, a full buffer, the byte image.
#include "firmware/can/capture_recorder.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "firmware/can/capture_channels.hpp"

namespace tnv::fw::can {
namespace {

TickRecord at(std::uint64_t tick, MotionState state, std::int64_t motion_tick = -1) {
  TickRecord r;
  r.tick = tick;
  r.state = state;
  r.motion_tick = motion_tick;
  r.axis[0].position_mm = 0.001 * static_cast<double>(tick);  // 1 um per tick
  r.axis[1].dac_code = static_cast<std::uint16_t>(tick);
  return r;
}

TEST(CaptureRecorder, ImmediateRecordsUntilTheBufferIsFull) {
  auto rec = std::make_unique<CaptureRecorder>();
  rec->arm({channel_mask_low(kAllCaptureChannels), channel_mask_high(kAllCaptureChannels), CaptureTrigger::immediate, 1});
  EXPECT_EQ(rec->state(), CaptureState::recording);
  const std::uint32_t capacity = kCaptureCapacityWords / static_cast<std::uint32_t>(kCaptureChannels.size());
  ASSERT_EQ(rec->capacity_samples(), capacity);
  std::uint64_t t = 0;
  while (rec->state() == CaptureState::recording && t < 10 * capacity) rec->on_tick(at(++t, MotionState::holding), {});
  EXPECT_EQ(rec->samples(), capacity);
  EXPECT_EQ(t, capacity) << "stopped at the tick that filled it";
  EXPECT_EQ(rec->state(), CaptureState::done);
  // Last sample: pos_x is channel 0; dac_y's word is at its channel's place.
  const std::size_t last = static_cast<std::size_t>(capacity - 1) * kCaptureChannels.size();
  EXPECT_EQ(static_cast<std::int32_t>(rec->words()[last]), static_cast<std::int32_t>(capacity) * 1000) << "nm";
  EXPECT_EQ(rec->words()[last + channel_bit("dac_y")], capacity & 0xFFFFu);
}

TEST(CaptureRecorder, TheImageIsLittleEndianWordsAndZeroPastTheEnd) {
  auto rec = std::make_unique<CaptureRecorder>();
  rec->arm({1u << 0, 0, CaptureTrigger::immediate, 1});
  rec->on_tick(at(0x123, MotionState::holding), {});  // pos_x = 0.291 mm = 291000 nm = 0x000470B8
  rec->abort();
  ASSERT_EQ(rec->image_bytes(), 4u);
  EXPECT_EQ(rec->image_byte(0), 0xB8);
  EXPECT_EQ(rec->image_byte(1), 0x70);
  EXPECT_EQ(rec->image_byte(2), 0x04);
  EXPECT_EQ(rec->image_byte(3), 0x00);
  EXPECT_EQ(rec->image_byte(4), 0x00);
}

TEST(CaptureRecorder, FaultTriggerStartsAtTheTickTheFaultLatches) {
  auto rec = std::make_unique<CaptureRecorder>();
  rec->on_tick(at(1, MotionState::faulted), {});  // an old fault, before arming
  rec->on_tick(at(2, MotionState::disabled), {});
  rec->arm({(1u << 0) | (1u << channel_bit("state")), 0, CaptureTrigger::fault, 2});
  for (std::uint64_t t = 3; t < 10; ++t) rec->on_tick(at(t, MotionState::moving, static_cast<std::int64_t>(t)), {});
  EXPECT_EQ(rec->state(), CaptureState::armed);
  for (std::uint64_t t = 10; t < 15; ++t) rec->on_tick(at(t, MotionState::faulted), {});
  EXPECT_EQ(rec->state(), CaptureState::recording);
  ASSERT_EQ(rec->samples(), 3u) << "ticks 10, 12, 14";
  EXPECT_EQ(rec->words()[0], 10'000u);
  EXPECT_EQ(rec->words()[2], 12'000u);
  EXPECT_EQ(rec->words()[5], static_cast<std::uint32_t>(MotionState::faulted));
}

TEST(CaptureRecorder, MotionTriggerSpansDwellAndMotionAndEndsAfterIt) {
  auto rec = std::make_unique<CaptureRecorder>();
  rec->arm({1u << channel_bit("motion_tick"), 0, CaptureTrigger::motion, 1});
  rec->on_tick(at(1, MotionState::holding), {});
  EXPECT_EQ(rec->state(), CaptureState::armed);
  rec->on_tick(at(2, MotionState::dwell), {});
  rec->on_tick(at(3, MotionState::moving, 0), {});
  rec->on_tick(at(4, MotionState::holding, 1), {});  // the motion's last tick
  rec->on_tick(at(5, MotionState::holding), {});
  EXPECT_EQ(rec->state(), CaptureState::done);
  ASSERT_EQ(rec->samples(), 3u);
  EXPECT_EQ(static_cast<std::int32_t>(rec->words()[0]), -1);
  EXPECT_EQ(rec->words()[2], 1u);
  rec->arm({1u << channel_bit("motion_tick"), 0, CaptureTrigger::motion, 1});
  EXPECT_EQ(rec->samples(), 0u) << "arming drops the old image";
}

}  // namespace
}  // namespace tnv::fw::can
