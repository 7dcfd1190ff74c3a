// The checked-in fuzz corpus as regression tests of the normal build: every
// file of tests/fuzz/corpus/<target>/ through the same entry the libFuzzer
// target calls (fuzz_entries.hpp), so a fix stays fixed in every CI build.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "firmware/can/can_id.hpp"
#include "firmware/can/frame_codec.hpp"
#include "tests/fuzz/fuzz_entries.hpp"
#include "tests/fuzz/fuzz_support.hpp"
#ifdef TNV_FUZZ_HTTP
#include "tests/fuzz/http_routes_entry.hpp"
#endif

namespace tnv {
namespace {

namespace fs = std::filesystem;
using Entry = std::string (*)(const std::uint8_t*, std::size_t);

// Returns how many files ran.
int run_corpus(const char* target, Entry entry) {
  const fs::path dir = fs::path(TNV_SOURCE_DIR) / "tests" / "fuzz" / "corpus" / target;
  int files = 0;
  if (!fs::is_directory(dir)) return 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    std::ifstream in(e.path(), std::ios::binary);
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(entry(bytes.data(), bytes.size()), "") << e.path().filename().string();
    ++files;
  }
  return files;
}

constexpr int kMinSeeds = 20;  // a corpus, not a token file

TEST(FuzzCorpus, CanFrames) { EXPECT_GE(run_corpus("can_frames", fuzz::can_frames), kMinSeeds); }
TEST(FuzzCorpus, FrameCodec) { EXPECT_GE(run_corpus("frame_codec", fuzz::frame_codec), kMinSeeds); }
TEST(FuzzCorpus, ParamSet) { EXPECT_GE(run_corpus("param_set", fuzz::param_set), kMinSeeds); }
TEST(FuzzCorpus, ScenarioToml) { EXPECT_GE(run_corpus("scenario_toml", fuzz::scenario_toml), kMinSeeds); }
TEST(FuzzCorpus, ParamImage) { EXPECT_GE(run_corpus("param_image", fuzz::param_image), kMinSeeds); }
TEST(FuzzCorpus, GcodeCanon) { EXPECT_GE(run_corpus("gcode_canon", fuzz::gcode_canon), kMinSeeds); }
#ifdef TNV_FUZZ_HTTP
TEST(FuzzCorpus, HttpRoutes) { EXPECT_GE(run_corpus("http_routes", fuzz::http_routes), kMinSeeds); }
#endif

// The can_frames seeds are written from the protocol's own frames
// (tnv-fuzz-seed), so nearly every seed carries a well-formed request to the
// fuzzed node (node 1, or broadcast): a seed whose identifiers are another
// protocol version's only reaches the node's "foreign frame" branch, and
// the fuzzer would start from there. The few seeds made of deliberately
// foreign or malformed frames (other nodes, extended, wrong lengths,
// to-host messages, an unknown id) are the allowance.
TEST(FuzzCorpus, CanFramesSeedsCarryRequestsToTheNodeInTodaysIdentifiers) {
  namespace can = fw::can;
  const fs::path dir = fs::path(TNV_SOURCE_DIR) / "tests" / "fuzz" / "corpus" / "can_frames";
  int seeds = 0, reaching = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    std::ifstream in(e.path(), std::ios::binary);
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    bool reaches = false;
    for (std::size_t r = 0; r + fuzz::kFrameRecordBytes <= bytes.size(); r += fuzz::kFrameRecordBytes) {
      const hal::CanFrame f = fuzz::frame_of_record(&bytes[r]);
      const can::MessageDef* m = f.extended ? nullptr : can::classify(f);
      const std::uint8_t node = can::node_of(f.id);
      reaches = reaches || (m != nullptr && m->direction == can::Direction::to_node && f.dlc == m->dlc &&
                            (node == 1 || node == can::kBroadcastNode));
    }
    ++seeds;
    if (reaches) ++reaching;
  }
  ASSERT_GE(seeds, kMinSeeds);
  EXPECT_GE(reaching, seeds - 6) << reaching << " of " << seeds << " seeds carry a request the node handles";
}

// The empty input (libFuzzer's first) is a valid input for every entry.
TEST(FuzzCorpus, EmptyInputsAreHandled) {
  EXPECT_EQ(fuzz::can_frames(nullptr, 0), "");
  EXPECT_EQ(fuzz::frame_codec(nullptr, 0), "");
  EXPECT_EQ(fuzz::param_set(nullptr, 0), "");
  EXPECT_EQ(fuzz::scenario_toml(reinterpret_cast<const std::uint8_t*>(""), 0), "");
  EXPECT_EQ(fuzz::param_image(nullptr, 0), "");
  EXPECT_EQ(fuzz::gcode_canon(reinterpret_cast<const std::uint8_t*>(""), 0), "");
}

}  // namespace
}  // namespace tnv
