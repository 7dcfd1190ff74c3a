// The boring planner's learned state in the parameter image (version 3):
// saved and loaded bit for bit, whole or not at all; a damaged or
// implausible state is refused like a damaged image, even under a good CRC;
// version 2 images (no state) still load.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <vector>

#include "firmware/can/param_fallback.hpp"
#include "firmware/can/param_image.hpp"
#include "tests/firmware/can/bore_frames.hpp"

namespace tnv::fw::can {
namespace {

// A set whose planner has learned something: five parts of S4's process through the station.
NodeSettings bore_learned_settings() {
  NodeSettings s = test::boring_settings();
  for (int part = 1; part <= 5; ++part) {
    const std::array<double, 2> infeed = current_infeeds_mm_rev(s.bore, s.bore_state, 2e-5);
    const std::array<double, 2> errors = {test::s4_bore_error_mm(test::s4_deflection_mm(part, infeed[0], 40.0, 0.02)),
                                          test::s4_bore_error_mm(test::s4_deflection_mm(part, infeed[1], 310.0, 0.02))};
    EXPECT_TRUE(record_bored_part(s.bore, s.bore_state, errors, 2e-5).check.ok);
  }
  return s;
}

std::vector<std::uint8_t> bore_image_of(const NodeSettings& s) {
  std::vector<std::uint8_t> buf(kParamImageMaxBytes);
  buf.resize(encode_image(s, buf));
  return buf;
}

void bore_reseal(std::vector<std::uint8_t>& img) {
  const std::size_t body = img.size() - kParamImageCrcBytes;
  const std::uint32_t c = crc32(std::span(img).first(body));
  for (std::size_t i = 0; i < 4; ++i) img[body + i] = static_cast<std::uint8_t>(c >> (8 * i));
}

// Offset of the bore-state block in an image.
std::size_t bore_block(const std::vector<std::uint8_t>& img) {
  return img.size() - kParamImageCrcBytes - kBoreStateImageBytes;
}

void put_u32(std::vector<std::uint8_t>& img, std::size_t at, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) img[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}
void put_f64(std::vector<std::uint8_t>& img, std::size_t at, double v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  for (std::size_t i = 0; i < 8; ++i) img[at + i] = static_cast<std::uint8_t>(bits >> (8 * i));
}

// Block offsets (bore_state_image.hpp): started, parts, resets, streak, 8 runs, theta[3], P[9], innovation, infeeds[2].
constexpr std::size_t kAtStarted = 0, kAtParts = 4, kAtStreak = 12, kAtTheta = 48, kAtCov = 72, kAtInfeed = 152;

TEST(ParamImageBore, TheLearnedStateRoundTripsBitForBit) {
  const NodeSettings learned = bore_learned_settings();
  ASSERT_TRUE(learned.bore_state.planner.started);
  NodeSettings back = test::boring_settings();
  ASSERT_EQ(decode_image(bore_image_of(learned), back), ErrorCode::ok);
  EXPECT_TRUE(back.bore_state == learned.bore_state);
  // Through storage too, as save_params and the start-up load do it.
  test::MemoryStorage storage;
  ASSERT_EQ(save_settings(storage, learned), ErrorCode::ok);
  NodeSettings loaded = test::boring_settings();
  ASSERT_EQ(load_settings(storage, loaded), ErrorCode::ok);
  EXPECT_TRUE(loaded.bore_state == learned.bore_state);
}

TEST(ParamImageBore, AnImplausibleStateUnderAGoodCrcIsRefusedAndNothingIsApplied) {
  const NodeSettings learned = bore_learned_settings();
  const std::vector<std::uint8_t> good = bore_image_of(learned);
  const std::size_t at = bore_block(good);
  struct Edit {
    const char* what;
    void (*apply)(std::vector<std::uint8_t>&, std::size_t);
  };
  const Edit edits[] = {
      {"started = 2", [](std::vector<std::uint8_t>& i, std::size_t a) { put_u32(i, a + kAtStarted, 2); }},
      {"not started, but learned", [](std::vector<std::uint8_t>& i, std::size_t a) { put_u32(i, a + kAtStarted, 0); }},
      {"parts -1", [](std::vector<std::uint8_t>& i, std::size_t a) { put_u32(i, a + kAtParts, 0xFFFFFFFFu); }},
      {"run of 1000", [](std::vector<std::uint8_t>& i, std::size_t a) { put_u32(i, a + kAtStreak, 1000); }},
      {"theta NaN", [](std::vector<std::uint8_t>& i, std::size_t a) {
         put_f64(i, a + kAtTheta + 8, std::numeric_limits<double>::quiet_NaN());
       }},
      {"P not symmetric", [](std::vector<std::uint8_t>& i, std::size_t a) { put_f64(i, a + kAtCov + 8, 0.25); }},
      {"P above P0", [](std::vector<std::uint8_t>& i, std::size_t a) { put_f64(i, a + kAtCov, 3.0); }},
      {"infeed 0 after start-up", [](std::vector<std::uint8_t>& i, std::size_t a) { put_f64(i, a + kAtInfeed, 0.0); }},
      {"infeed inf", [](std::vector<std::uint8_t>& i, std::size_t a) {
         put_f64(i, a + kAtInfeed + 8, std::numeric_limits<double>::infinity());
       }},
  };
  for (const Edit& e : edits) {
    std::vector<std::uint8_t> bad = good;
    e.apply(bad, at);
    ASSERT_NE(bad, good) << e.what << ": the edit changed nothing";
    bore_reseal(bad);
    NodeSettings s = test::boring_settings();
    const std::vector<std::uint8_t> before = bore_image_of(s);
    EXPECT_EQ(decode_image(bad, s), ErrorCode::storage_corrupt) << e.what;
    EXPECT_EQ(bore_image_of(s), before) << e.what << ": half applied";
  }
  // The unedited image, resealed, still loads: the edits were the cause.
  std::vector<std::uint8_t> same = good;
  bore_reseal(same);
  NodeSettings s = test::boring_settings();
  EXPECT_EQ(decode_image(same, s), ErrorCode::ok);
}

TEST(ParamImageBore, AStartUpLoadFallsBackToThePreviousImageWhenTheCurrentStateIsDamaged) {
  const NodeSettings older = bore_learned_settings();
  NodeSettings newer = older;
  const std::array<double, 2> infeed = current_infeeds_mm_rev(newer.bore, newer.bore_state, 2e-5);
  ASSERT_TRUE(record_bored_part(newer.bore, newer.bore_state, {0.01 * infeed[0], 0.0}, 2e-5).check.ok);
  test::MemoryStorage current;
  test::MemoryStorage previous;
  previous.bytes = bore_image_of(older);
  previous.present = true;
  current.bytes = bore_image_of(newer);
  stamp_generation(current.bytes, 2);
  current.bytes[bore_block(current.bytes) + kAtCov + 8] ^= 0x40;  // one covariance entry damaged ...
  bore_reseal(current.bytes);                                     // ... under a good CRC
  current.present = true;
  NodeSettings s = test::boring_settings();
  const LoadReport r = load_settings_with_fallback(current, &previous, s);
  EXPECT_EQ(r.source, LoadSource::previous);
  EXPECT_EQ(r.current, ErrorCode::storage_corrupt);
  EXPECT_TRUE(r.fault());
  EXPECT_TRUE(s.bore_state == older.bore_state) << "the previous generation's learning, whole";
}

TEST(ParamImageBore, AVersionTwoImageStillLoadsAndKeepsTheLearningItDoesNotCarry) {
  const NodeSettings learned = bore_learned_settings();
  NodeSettings other = test::boring_settings();
  other.bore.alpha0 = static_cast<double>(0.75f);
  std::vector<std::uint8_t> v2 = bore_image_of(other);
  v2.erase(v2.begin() + static_cast<std::ptrdiff_t>(bore_block(v2)), v2.end() - kParamImageCrcBytes);
  v2[4] = kParamImageVersion2;
  bore_reseal(v2);
  std::uint32_t generation = 0;
  ASSERT_TRUE(image_generation(v2, generation));
  NodeSettings s = learned;
  ASSERT_EQ(decode_image(v2, s), ErrorCode::ok);
  EXPECT_EQ(s.bore.alpha0, static_cast<double>(0.75f)) << "its parameters load";
  EXPECT_TRUE(s.bore_state == learned.bore_state) << "the learning it does not carry stays";
  NodeSettings fresh = test::boring_settings();
  ASSERT_EQ(decode_image(v2, fresh), ErrorCode::ok);
  EXPECT_TRUE(fresh.bore_state == BoringStationState{}) << "at start-up: a planner that has learned nothing";
}

}  // namespace
}  // namespace tnv::fw::can
