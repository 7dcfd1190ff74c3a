// On-target capture end to end on the emulated TNV-40: arm with the
// motion trigger, run over CAN, upload in segments, reassemble, and check
// every recorded value against the tick's own TickRecord; the captured
// circle scores exactly as tnv-hil's run_circle() scores the same circle.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <map>
#include <vector>

#include "firmware/can/capture_channels.hpp"
#include "tests/hil/can_node_rig.hpp"
#include "tools/hil/circle_run.hpp"
#include "tools/score/contour_stats.hpp"

namespace tnv::test {
namespace {

using fw::can::CaptureOp;
using fw::can::ErrorCode;
using fw::can::MessageId;


// Encoded here, independently of the firmware's channel code.
std::uint32_t nm(double mm) { return static_cast<std::uint32_t>(static_cast<std::int32_t>(std::llround(mm * 1e6))); }
std::uint32_t f32(double v) { return std::bit_cast<std::uint32_t>(static_cast<float>(v)); }

// The whole image, uploaded in blocks of up to 255 frames; nullopt-like empty on a protocol error.
std::vector<std::uint8_t> upload(CanRig& r, std::uint32_t image_bytes, int& blocks) {
  std::vector<std::uint8_t> image;
  blocks = 0;
  while (image.size() < image_bytes) {
    const auto offset = static_cast<std::uint32_t>(image.size());
    const std::uint32_t frames = std::min<std::uint32_t>(255, (image_bytes - offset + 6) / 7);
    r.port.send(capture_control(kRigNode, CaptureOp::upload, static_cast<std::uint8_t>(frames), offset));
    std::vector<hal::CanFrame> got;
    for (int k = 0; k < 100 && got.size() < frames; ++k) {
      r.node->service();  // no tick needed: the upload goes over as many services as it takes
      for (const hal::CanFrame& f : r.port.drain()) got.push_back(f);
    }
    if (got.size() != frames) return {};
    for (std::uint32_t i = 0; i < frames; ++i) {
      if (!is(got[i], MessageId::capture_data) || raw_of(got[i], MessageId::capture_data, "sequence") != i) return {};
      for (int b = 1; b < 8 && image.size() < image_bytes; ++b) image.push_back(got[i].data[static_cast<std::size_t>(b)]);
    }
    ++blocks;
  }
  return image;
}

std::uint32_t word(const std::vector<std::uint8_t>& image, std::size_t w) {
  return static_cast<std::uint32_t>(image[4 * w]) | static_cast<std::uint32_t>(image[4 * w + 1]) << 8 |
         static_cast<std::uint32_t>(image[4 * w + 2]) << 16 | static_cast<std::uint32_t>(image[4 * w + 3]) << 24;
}

TEST(CanNodeCapture, AFullCircleCapturedOverCanScoresExactlyLikeTnvHil) {
  auto r = CanRig::make("no-cut", fw::ControllerKind::rdvsc);
  ASSERT_TRUE(r);
  const hil::CircleRunResult reference = hil::run_circle(r->scenario, fw::default_firmware_config(), fw::ControllerKind::rdvsc);
  ASSERT_TRUE(reference.completed) << reference.error;

  const std::vector<hal::CanFrame> armed = r->request(capture_control(kRigNode, CaptureOp::arm));
  ASSERT_EQ(armed.size(), 1u);
  EXPECT_EQ(raw_of(armed[0], MessageId::capture_status, "state"), static_cast<std::uint32_t>(fw::can::CaptureState::armed));
  EXPECT_EQ(raw_of(armed[0], MessageId::capture_status, "channels"), 6u) << "the default set";
  ASSERT_EQ(r->result(circle(kRigNode, r->scenario.circle.radius_mm, r->scenario.circle.feed_mm_s)), kOk);
  std::map<std::uint64_t, fw::TickRecord> records;  // every tick's record, by tick
  for (int k = 0; k < 25'000 && r->task().state() != fw::MotionState::holding; ++k) {
    r->step();
    records[r->task().last_record().tick] = r->task().last_record();
  }
  ASSERT_EQ(r->task().state(), fw::MotionState::holding);
  ASSERT_EQ(r->node->capture_state(), fw::can::CaptureState::done);

  const std::vector<hal::CanFrame> status = r->request(capture_control(kRigNode, CaptureOp::status));
  ASSERT_EQ(status.size(), 1u);
  const std::uint32_t samples = raw_of(status[0], MessageId::capture_status, "samples");
  EXPECT_EQ(samples, r->node->capture_samples());
  int blocks = 0;
  const std::vector<std::uint8_t> image = upload(*r, samples * 6 * 4, blocks);
  ASSERT_EQ(image.size(), samples * 6u * 4u) << "upload failed";
  EXPECT_GT(blocks, 100) << "a segmented transfer";

  // Sample j is tick first + j (decimation 1): the trigger is the first dwell tick, the last
  // sample the tick the circle ends.
  const std::uint64_t first = records.begin()->first;
  ASSERT_EQ(samples, records.size());
  hil::ContourAccumulator from_channel;
  hil::ContourAccumulator from_positions;
  std::size_t scored = 0;
  for (std::uint32_t j = 0; j < samples; ++j) {
    const fw::TickRecord& rec = records.at(first + j);
    const std::size_t w = static_cast<std::size_t>(j) * 6;  // pos_x pos_y ref_x ref_y contour motion_tick
    ASSERT_EQ(word(image, w + 0), nm(rec.axis[0].position_mm)) << "sample " << j;
    ASSERT_EQ(word(image, w + 1), nm(rec.axis[1].position_mm)) << "sample " << j;
    ASSERT_EQ(word(image, w + 2), nm(rec.axis[0].reference_mm)) << "sample " << j;
    ASSERT_EQ(word(image, w + 3), nm(rec.axis[1].reference_mm)) << "sample " << j;
    const auto motion_tick = static_cast<std::int32_t>(word(image, w + 5));
    ASSERT_EQ(motion_tick, rec.motion_tick) << "sample " << j;
    const double e_mm = hil::contour_error_mm(rec.axis[0].reference_mm, rec.axis[1].reference_mm, rec.axis[0].position_mm,
                                              rec.axis[1].position_mm);
    ASSERT_EQ(word(image, w + 4), f32(motion_tick >= 0 ? e_mm * 1000.0 : 0.0)) << "sample " << j;
    if (motion_tick < 0) continue;
    ++scored;
    from_channel.add(static_cast<double>(std::bit_cast<float>(word(image, w + 4))) / 1000.0);
    const auto mm = [&](std::size_t k) { return static_cast<double>(static_cast<std::int32_t>(word(image, w + k))) * 1e-6; };
    from_positions.add(hil::contour_error_mm(mm(2), mm(3), mm(0), mm(1)));
  }
  EXPECT_EQ(scored, reference.stats.samples) << "the same ticks are scored";
  const hil::ContourStats c = from_channel.stats();
  const hil::ContourStats p = from_positions.stats();
  // The channel is the float of the very number tnv-hil scores: equal to float precision.
  EXPECT_NEAR(c.max_um, reference.stats.max_um, 1e-6 * reference.stats.max_um);
  EXPECT_NEAR(c.mean_um, reference.stats.mean_um, 1e-6 * reference.stats.mean_um);
  EXPECT_NEAR(c.std_um, reference.stats.std_um, 1e-6 * reference.stats.std_um);
  // From the nanometre positions: within the rounding (2 nm on the difference of two radii).
  EXPECT_NEAR(p.max_um, reference.stats.max_um, 2e-3);
  EXPECT_NEAR(p.mean_um, reference.stats.mean_um, 2e-3);
}

TEST(CanNodeCapture, DecimationRecordsEveryNthTickAndTheTickTheMoveEnds) {
  auto r = CanRig::make();
  ASSERT_TRUE(r);
  using fw::can::channel_bit;
  const std::uint32_t mask = (1u << channel_bit("pos_x")) | (1u << channel_bit("speed_x")) |
                             (1u << channel_bit("command_x")) | (1u << channel_bit("dac_x")) |
                             (1u << channel_bit("motion_tick")) | (1u << channel_bit("state"));
  ASSERT_EQ(r->result(param_request(kRigNode, fw::can::ParamOp::set, param_id("capture.channels"), mask)), kOk);
  ASSERT_EQ(r->result(param_request(kRigNode, fw::can::ParamOp::set, param_id("capture.decimation"), 3)), kOk);
  ASSERT_EQ(r->result(command(kRigNode, fw::can::CommandCode::enable)), kOk);
  r->step();
  ASSERT_EQ(r->result(capture_control(kRigNode, CaptureOp::arm)), kOk);
  for (int k = 0; k < 20; ++k) r->step();
  EXPECT_EQ(r->node->capture_state(), fw::can::CaptureState::armed) << "holding is not motion";
  ASSERT_EQ(r->result(move(kRigNode, 0, 20.0, -2.0)), kOk);
  std::vector<fw::TickRecord> records;
  while (r->task().state() != fw::MotionState::holding && records.size() < 1000) {
    r->step();
    records.push_back(r->task().last_record());
  }
  ASSERT_EQ(r->node->capture_state(), fw::can::CaptureState::done);
  const std::size_t n = records.size();  // ticks of motion, the last one ends it
  const std::size_t expected = (n - 1) / 3 + 1 + ((n - 1) % 3 == 0 ? 0 : 1);
  ASSERT_EQ(r->node->capture_samples(), expected);
  int blocks = 0;
  const std::vector<std::uint8_t> image = upload(*r, static_cast<std::uint32_t>(expected * 6 * 4), blocks);
  ASSERT_EQ(image.size(), expected * 24);
  for (std::size_t j = 0; j < expected; ++j) {
    const fw::TickRecord& rec = records[std::min(3 * j, n - 1)];
    const std::size_t w = j * 6;  // pos_x speed_x command_x dac_x motion_tick state
    EXPECT_EQ(word(image, w + 0), nm(rec.axis[0].position_mm)) << j;
    EXPECT_EQ(word(image, w + 1), f32(rec.axis[0].speed_mm_s)) << j;
    EXPECT_EQ(word(image, w + 2), f32(rec.axis[0].command_mm_s)) << j;
    EXPECT_EQ(word(image, w + 3), rec.axis[0].dac_code) << j;
    EXPECT_EQ(static_cast<std::int32_t>(word(image, w + 4)), rec.motion_tick) << j;
    EXPECT_EQ(word(image, w + 5), static_cast<std::uint32_t>(rec.state)) << j;
  }
  EXPECT_EQ(word(image, (expected - 1) * 6 + 5), static_cast<std::uint32_t>(fw::MotionState::holding))
      << "the last sample is the tick the move ended";

  // Past the end: not_ready; the last partial frame is zero-padded.
  const std::vector<hal::CanFrame> past =
      r->request(capture_control(kRigNode, CaptureOp::upload, 1, static_cast<std::uint32_t>(image.size())));
  ASSERT_EQ(past.size(), 1u);
  EXPECT_TRUE(is(past[0], MessageId::capture_status));
  EXPECT_EQ(raw_of(past[0], MessageId::capture_status, "result"), static_cast<std::uint32_t>(ErrorCode::not_ready));
  const std::vector<hal::CanFrame> tail =
      r->request(capture_control(kRigNode, CaptureOp::upload, 1, static_cast<std::uint32_t>(image.size() - 3)));
  ASSERT_EQ(tail.size(), 1u);
  EXPECT_TRUE(is(tail[0], MessageId::capture_data));
  for (std::size_t b = 0; b < 3; ++b) EXPECT_EQ(tail[0].data[1 + b], image[image.size() - 3 + b]);
  for (std::size_t b = 4; b < 8; ++b) EXPECT_EQ(tail[0].data[b], 0) << "zero past the end";
}

TEST(CanNodeCapture, UploadWhileRecordingIsBusyAndAbortKeepsWhatWasRecorded) {
  auto r = CanRig::make();
  ASSERT_TRUE(r);
  ASSERT_EQ(r->result(param_request(kRigNode, fw::can::ParamOp::set, param_id("capture.trigger"), 0)), kOk);  // immediate
  ASSERT_EQ(r->result(capture_control(kRigNode, CaptureOp::arm)), kOk);
  for (int k = 0; k < 40; ++k) r->step();
  EXPECT_EQ(r->node->capture_state(), fw::can::CaptureState::recording);
  EXPECT_NE(r->node->heartbeat_errors() & fw::can::kHbCaptureRecording, 0);
  EXPECT_EQ(r->result(capture_control(kRigNode, CaptureOp::upload, 10, 0)), static_cast<std::uint32_t>(ErrorCode::busy));
  EXPECT_EQ(r->result(capture_control(kRigNode, CaptureOp::abort)), kOk);
  EXPECT_EQ(r->node->capture_state(), fw::can::CaptureState::done);
  EXPECT_EQ(r->node->capture_samples(), 40u);
  EXPECT_NE(r->node->heartbeat_errors() & fw::can::kHbCaptureDone, 0);
  r->port.send(capture_control(kRigNode, CaptureOp::upload, 3, 0));
  r->node->service();
  EXPECT_EQ(only(r->port.drain(), MessageId::capture_data).size(), 3u);
}

}  // namespace
}  // namespace tnv::test
