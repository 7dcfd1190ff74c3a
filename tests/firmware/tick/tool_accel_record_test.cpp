// The tool-side accelerometer from the board's ADC_ACCEL codes to the tick
// record (mm/s^2) and to the CAN capture channels accel_x / accel_y.
#include <gtest/gtest.h>

#include "firmware/can/capture_channels.hpp"
#include "firmware/can/capture_recorder.hpp"
#include "firmware/can/frame_codec.hpp"
#include "firmware/io/accel_code.hpp"
#include "firmware/tick/tick_task.hpp"
#include "hal/io_board_registers.hpp"
#include "tests/firmware/fake_io_board.hpp"

namespace tnv::fw {
namespace {

constexpr double kAccelLsb_mm_s2 = hal::regs::kAccelFullScaleMmS2 / 2048.0;

TEST(ToolAccelCode, OffsetBinaryAroundMidScale) {
  EXPECT_EQ(accel_code_to_mm_s2(2048), 0.0);
  EXPECT_DOUBLE_EQ(accel_code_to_mm_s2(0), -hal::regs::kAccelFullScaleMmS2);
  EXPECT_DOUBLE_EQ(accel_code_to_mm_s2(4095), hal::regs::kAccelFullScaleMmS2 - kAccelLsb_mm_s2);
  EXPECT_NEAR(kAccelLsb_mm_s2, 9.5768, 1e-3) << "mm/s^2 per LSB at +-2 g";
}

TEST(ToolAccelRecord, EachTickRecordsBothAxesAndTheCaptureSendsThem) {
  tnv::test::FakeIoBoard board;
  TickTask task(board, default_firmware_config());
  board.accel_code = {2048 + 100, 2048 - 7};
  board.next_tick();
  task.tick();
  const TickRecord& r = task.last_record();
  EXPECT_DOUBLE_EQ(r.axis[0].accel_mm_s2, 100 * kAccelLsb_mm_s2);
  EXPECT_DOUBLE_EQ(r.axis[1].accel_mm_s2, -7 * kAccelLsb_mm_s2);
  constexpr std::uint8_t kX = can::channel_bit("accel_x"), kY = can::channel_bit("accel_y");
  const can::ChannelDef* x = can::find_channel(kX);
  const can::ChannelDef* y = can::find_channel(kY);
  ASSERT_NE(x, nullptr);
  ASSERT_NE(y, nullptr);
  EXPECT_EQ(x->kind, can::ChannelKind::accel);
  EXPECT_EQ(y->kind, can::ChannelKind::accel);
  const can::TickSignals sig{};
  EXPECT_EQ(can::channel_word(kX, r, sig), can::float_bits(static_cast<float>(100 * kAccelLsb_mm_s2)));
  EXPECT_EQ(can::channel_word(kY, r, sig), can::float_bits(static_cast<float>(-7 * kAccelLsb_mm_s2)));
}

}  // namespace
}  // namespace tnv::fw
