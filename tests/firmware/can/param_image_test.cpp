// The stored parameter image: exact round trip, and every kind of damage
// refused whole (nothing applied).
#include "firmware/can/param_image.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "firmware/can/param_fallback.hpp"
#include "firmware/can/param_table.hpp"
#include "tests/firmware/can/can_test_doubles.hpp"

namespace tnv::fw::can {
namespace {

// default_node_settings() runs the PID tuning rule: compute it once.
const NodeSettings& defaults() {
  static const NodeSettings d = default_node_settings();
  return d;
}

// A set that differs from the defaults in a float, an integer, an enum and a bool.
NodeSettings tuned() {
  NodeSettings s = defaults();
  s.firmware.axis[0].sliding.gamma = static_cast<double>(0.3141f);
  s.firmware.axis[1].pid.kp = static_cast<double>(512.25f);
  s.firmware.axis[1].controller = ControllerKind::pid;
  s.telemetry.position_ms = 7;
  s.shaper[0].enabled = true;
  s.shaper[0].spec.mode.freq_hz = static_cast<double>(31.5f);
  s.can.node_id = 12;
  return s;
}

std::vector<std::uint8_t> image_of(const NodeSettings& s) {
  std::vector<std::uint8_t> buf(kParamImageMaxBytes);
  buf.resize(encode_image(s, buf));
  return buf;
}

bool same_params(const NodeSettings& a, const NodeSettings& b) {
  for (const ParamDef& p : param_table())
    if (p.get(a) != p.get(b)) return false;
  return true;
}

TEST(ParamImage, EveryReadWriteParameterFitsAndRoundTripsExactly) {
  std::size_t rw = 0;
  for (const ParamDef& p : param_table()) rw += p.access == Access::read_write ? 1 : 0;
  ASSERT_LE(rw, kParamImageMaxEntries);
  const std::vector<std::uint8_t> img = image_of(tuned());
  ASSERT_EQ(img.size(),
            kParamImageHeaderBytes + rw * kParamImageEntryBytes + kBoreStateImageBytes + kParamImageCrcBytes);
  NodeSettings back = defaults();
  ASSERT_EQ(decode_image(img, back), ErrorCode::ok);
  EXPECT_TRUE(same_params(back, tuned()));
  EXPECT_EQ(back.firmware.axis[0].sliding.gamma, static_cast<double>(0.3141f));
  EXPECT_EQ(back.firmware.axis[1].controller, ControllerKind::pid);
  EXPECT_EQ(back.can.node_id, 12u);
}

TEST(ParamImage, Crc32IsTheIeeeCheckValue) {
  const std::uint8_t digits[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(crc32(digits), 0xCBF43926u);
}

TEST(ParamImage, AnyCorruptedByteIsRefusedAndNothingIsApplied) {
  const std::vector<std::uint8_t> good = image_of(tuned());
  for (std::size_t i = 0; i < good.size(); ++i) {
    std::vector<std::uint8_t> bad = good;
    bad[i] ^= 0x10;
    NodeSettings s = defaults();
    EXPECT_EQ(decode_image(bad, s), ErrorCode::storage_corrupt) << "byte " << i;
    EXPECT_TRUE(same_params(s, defaults())) << "byte " << i;
  }
}

TEST(ParamImage, TruncatedOrExtendedImagesAreRefused) {
  const std::vector<std::uint8_t> good = image_of(tuned());
  for (const std::size_t n : {std::size_t{0}, std::size_t{7}, std::size_t{12}, good.size() - 11, good.size() - 1}) {
    NodeSettings s = defaults();
    EXPECT_EQ(decode_image(std::span(good).first(n), s), ErrorCode::storage_corrupt) << n << " bytes";
    EXPECT_TRUE(same_params(s, defaults()));
  }
  std::vector<std::uint8_t> longer = good;
  longer.push_back(0);
  NodeSettings s = defaults();
  EXPECT_EQ(decode_image(longer, s), ErrorCode::storage_corrupt);
}

// Re-seals an edited image with a correct CRC, so only the edit is wrong.
void reseal(std::vector<std::uint8_t>& img) {
  const std::size_t body = img.size() - kParamImageCrcBytes;
  const std::uint32_t c = crc32(std::span(img).first(body));
  for (std::size_t i = 0; i < 4; ++i) img[body + i] = static_cast<std::uint8_t>(c >> (8 * i));
}

TEST(ParamImage, WrongVersionUnknownIdBadValueAndInvalidSetAreRefusedEvenWithAGoodCrc) {
  const std::vector<std::uint8_t> good = image_of(tuned());
  std::vector<std::uint8_t> version = good;
  version[4] = kParamImageVersion + 1;
  reseal(version);
  std::vector<std::uint8_t> unknown = good;
  unknown[kParamImageHeaderBytes] = 0xFE;  // first entry's id -> 0x..FE
  unknown[kParamImageHeaderBytes + 1] = 0x7F;
  reseal(unknown);
  std::vector<std::uint8_t> read_only = good;
  read_only[kParamImageHeaderBytes] = 0x00;  // sys.protocol_version
  read_only[kParamImageHeaderBytes + 1] = 0x00;
  reseal(read_only);
  for (const auto* img : {&version, &unknown, &read_only}) {
    NodeSettings s = defaults();
    EXPECT_EQ(decode_image(*img, s), ErrorCode::storage_corrupt);
    EXPECT_TRUE(same_params(s, defaults()));
  }
  // Each value in range, the set not: phi below eta / (q + 1).
  NodeSettings inconsistent = defaults();
  inconsistent.firmware.axis[0].sliding.eta_mm_s = 2.0;
  inconsistent.firmware.axis[0].sliding.phi_mm_s = 0.5;
  NodeSettings s = defaults();
  EXPECT_EQ(decode_image(image_of(inconsistent), s), ErrorCode::invalid);
  EXPECT_TRUE(same_params(s, defaults()));
}

TEST(ParamImage, EncodeRefusesABufferTooSmall) {
  std::vector<std::uint8_t> small(20);
  EXPECT_EQ(encode_image(defaults(), small), 0u);
}

TEST(ParamImage, SaveAndLoadThroughTheStorageInterface) {
  test::MemoryStorage storage;
  NodeSettings s = defaults();
  EXPECT_EQ(load_settings(storage, s), ErrorCode::ok) << "nothing stored: ok";
  EXPECT_TRUE(same_params(s, defaults())) << "nothing stored: unchanged";
  ASSERT_EQ(save_settings(storage, tuned()), ErrorCode::ok);
  EXPECT_EQ(load_settings(storage, s), ErrorCode::ok);
  EXPECT_TRUE(same_params(s, tuned()));

  storage.bytes[storage.bytes.size() / 2] ^= 1;
  NodeSettings d = defaults();
  EXPECT_EQ(load_settings(storage, d), ErrorCode::storage_corrupt);
  EXPECT_TRUE(same_params(d, defaults()));

  storage.fail_read = true;
  EXPECT_EQ(load_settings(storage, d), ErrorCode::storage_error);
  storage.fail_write = true;
  EXPECT_EQ(save_settings(storage, tuned()), ErrorCode::storage_error);
}

std::uint32_t generation_of(const std::vector<std::uint8_t>& image) {
  std::uint32_t g = 0;
  EXPECT_TRUE(image_generation(image, g)) << "not an intact image";
  return g;
}

TEST(ParamImageGeneration, EachSaveStampsOneMoreThanTheImageItReplaces) {
  test::MemoryStorage storage;
  ASSERT_EQ(save_settings(storage, tuned()), ErrorCode::ok);
  EXPECT_EQ(generation_of(storage.bytes), 1u) << "the first save";
  ASSERT_EQ(save_settings(storage, defaults()), ErrorCode::ok);
  EXPECT_EQ(generation_of(storage.bytes), 2u);
  storage.bytes[storage.bytes.size() / 2] ^= 1;  // damaged: the next save starts again at 1
  ASSERT_EQ(save_settings(storage, defaults()), ErrorCode::ok);
  EXPECT_EQ(generation_of(storage.bytes), 1u);
}

TEST(ParamImageGeneration, AVersionOneImageStillLoadsAsGenerationZero) {
  // Version 1: the same image without the 4-byte generation and the bore state, version field 1.
  std::vector<std::uint8_t> v3 = image_of(tuned());
  std::vector<std::uint8_t> v1(v3.begin(), v3.begin() + 8);
  v1[4] = kParamImageVersion1;
  v1.insert(v1.end(), v3.begin() + static_cast<std::ptrdiff_t>(kParamImageHeaderBytes),
            v3.end() - static_cast<std::ptrdiff_t>(kBoreStateImageBytes + kParamImageCrcBytes));
  const std::uint32_t crc = crc32(v1);
  for (int i = 0; i < 4; ++i) v1.push_back(static_cast<std::uint8_t>(crc >> (8 * i)));
  NodeSettings s = defaults();
  ASSERT_EQ(decode_image(v1, s), ErrorCode::ok);
  EXPECT_TRUE(same_params(s, tuned()));
  EXPECT_EQ(generation_of(v1), 0u);
}

struct TwoGenerations {
  test::MemoryStorage current;
  test::MemoryStorage previous;
  void store(const NodeSettings& cur, std::uint32_t cur_gen, const NodeSettings& prev, std::uint32_t prev_gen) {
    current.bytes = image_of(cur);
    stamp_generation(current.bytes, cur_gen);
    previous.bytes = image_of(prev);
    stamp_generation(previous.bytes, prev_gen);
    current.present = true;
    previous.present = true;
  }
};

TEST(ParamImageGeneration, ACurrentImageOlderThanThePreviousIsARollbackAndTheNewerSetLoads) {
  TwoGenerations g;
  g.store(defaults(), 6, tuned(), 7);  // files swapped, or an old copy put back as the current one
  NodeSettings s = defaults();
  const LoadReport r = load_settings_with_fallback(g.current, &g.previous, s);
  EXPECT_EQ(r.source, LoadSource::rolled_back);
  EXPECT_TRUE(r.fault()) << "a rollback is a storage fault";
  EXPECT_EQ(r.result(), ErrorCode::ok);
  EXPECT_EQ(r.current_generation, 6u);
  EXPECT_EQ(r.previous_generation, 7u);
  EXPECT_TRUE(same_params(s, tuned())) << "the newer generation, whole";
}

TEST(ParamImageGeneration, NewerOrEqualCurrentGenerationsLoadCleanly) {
  for (const std::uint32_t prev_gen : {6u, 7u}) {  // 7 = 7: a save cut between keeping .prev and the rename
    TwoGenerations g;
    g.store(tuned(), 7, defaults(), prev_gen);
    NodeSettings s = defaults();
    const LoadReport r = load_settings_with_fallback(g.current, &g.previous, s);
    EXPECT_EQ(r.source, LoadSource::current) << "previous generation " << prev_gen;
    EXPECT_FALSE(r.fault());
    EXPECT_TRUE(same_params(s, tuned()));
  }
}

TEST(ParamImageGeneration, ADamagedNewerPreviousImageDoesNotOverrideAnIntactCurrentOne) {
  TwoGenerations g;
  g.store(tuned(), 3, defaults(), 9);
  g.previous.bytes[g.previous.bytes.size() / 2] ^= 1;
  NodeSettings s = defaults();
  const LoadReport r = load_settings_with_fallback(g.current, &g.previous, s);
  EXPECT_EQ(r.source, LoadSource::current);
  EXPECT_TRUE(same_params(s, tuned()));
}

}  // namespace
}  // namespace tnv::fw::can
