// drivers::FileParamStorage with the firmware's two-generation loader: a
// save is atomic (a writer killed anywhere leaves the old or the new set,
// bit-exact), a damaged current image falls back to the previous one, then
// to the defaults, and a directory that cannot be written refuses the save
// with a message naming the file and changes nothing.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "drivers/storage/file_param_storage.hpp"
#include "firmware/can/param_fallback.hpp"
#include "firmware/can/param_image.hpp"
#include "tests/sanitized_build.hpp"

namespace tnv {
namespace {

namespace can = fw::can;
namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

const can::NodeSettings& defaults() {
  static const can::NodeSettings d = can::default_node_settings();
  return d;
}

// Two valid sets that differ in several stored parameters.
can::NodeSettings set_a() {
  can::NodeSettings s = defaults();
  s.firmware.axis[0].sliding.gamma = 0.25;
  s.firmware.axis[1].sliding.gamma = 0.375;
  return s;
}
can::NodeSettings set_b() {
  can::NodeSettings s = defaults();
  s.firmware.axis[0].sliding.gamma = 0.5;
  s.firmware.axis[1].sliding.gamma = 0.125;
  return s;
}

Bytes image_of(const can::NodeSettings& s) {
  Bytes out(can::kParamImageMaxBytes);
  out.resize(can::encode_image(s, out));
  return out;
}

Bytes file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void put_file(const std::string& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

// A fresh directory per test (removed again at the end), in memory where
// /dev/shm exists: the loops here rewrite files thousands of times, and on
// ext4 every truncating rewrite is flushed to disk. What they test (which
// bytes a file holds after a rename or a kill) does not depend on the disk.
struct TempDir {
  explicit TempDir(const std::string& name) {
    std::string leaf = "tnv_storage_";
    leaf.append(std::to_string(::getpid())).append("_").append(name);
    const fs::path base = fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    path = base / leaf;
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::permissions(path, fs::perms::owner_all, ec);
    fs::remove_all(path, ec);
  }
  std::string file(const char* leaf) const { return (path / leaf).string(); }
  fs::path path;
};

// What a node would start with from `storage`: the report and the set, as an image.
struct Loaded {
  can::LoadReport report;
  Bytes image;
};
Loaded load(drivers::FileParamStorage& storage) {
  can::NodeSettings s = defaults();
  Loaded l;
  l.report = can::load_settings_with_fallback(storage, &storage.previous(), s);
  l.image = image_of(s);
  return l;
}

TEST(FileParamStorage, ASaveKeepsThePreviousGenerationAndThePreviousIsReadOnly) {
  const TempDir dir("rotate");
  drivers::FileParamStorage storage(dir.file("node.params"));
  ASSERT_EQ(storage.write(image_of(set_a())), hal::HalStatus::ok) << storage.last_error();
  EXPECT_FALSE(fs::exists(storage.previous_path())) << "nothing before the first save";
  ASSERT_EQ(storage.write(image_of(set_b())), hal::HalStatus::ok) << storage.last_error();
  EXPECT_EQ(file_bytes(storage.path()), image_of(set_b()));
  EXPECT_EQ(file_bytes(storage.previous_path()), image_of(set_a()));
  EXPECT_FALSE(fs::exists(storage.path() + ".tmp"));
  EXPECT_FALSE(fs::exists(storage.path() + ".prev.tmp"));
  const Bytes garbage(16, 0xAB);
  EXPECT_NE(storage.previous().write(garbage), hal::HalStatus::ok);
  EXPECT_EQ(file_bytes(storage.previous_path()), image_of(set_a()));
  const Loaded l = load(storage);
  EXPECT_EQ(l.report.source, can::LoadSource::current);
  EXPECT_FALSE(l.report.fault());
  EXPECT_EQ(l.image, image_of(set_b()));
}

TEST(FileParamStorage, EveryFlippedBitOfTheCurrentImageLoadsThePreviousSetWithAFault) {
  const TempDir dir("flip");
  drivers::FileParamStorage storage(dir.file("node.params"));
  ASSERT_EQ(storage.write(image_of(set_a())), hal::HalStatus::ok);
  ASSERT_EQ(storage.write(image_of(set_b())), hal::HalStatus::ok);
  const Bytes good = image_of(set_b());
  // Under a sanitizer every 7th bit: a step below 8 still hits every byte.
  const std::size_t step = tnv::test::kSanitizedBuild ? 7 : 1;
  int checked = 0;
  for (std::size_t index = 0; index < good.size() * 8; index += step) {
    const std::size_t byte = index / 8;
    const unsigned bit = static_cast<unsigned>(index % 8);
    Bytes bad = good;
    bad[byte] = static_cast<std::uint8_t>(bad[byte] ^ (1u << bit));
    put_file(storage.path(), bad);
    const Loaded l = load(storage);
    ASSERT_EQ(l.report.source, can::LoadSource::previous) << "byte " << byte << " bit " << bit;
    ASSERT_TRUE(l.report.fault());
    ASSERT_NE(l.report.current, can::ErrorCode::ok);
    ASSERT_EQ(l.image, image_of(set_a())) << "byte " << byte << " bit " << bit << ": not the previous set";
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>((good.size() * 8 + step - 1) / step));
}

TEST(FileParamStorage, ACurrentImageTruncatedAtAnyLengthLoadsThePreviousSet) {
  const TempDir dir("truncate");
  drivers::FileParamStorage storage(dir.file("node.params"));
  ASSERT_EQ(storage.write(image_of(set_a())), hal::HalStatus::ok);
  ASSERT_EQ(storage.write(image_of(set_b())), hal::HalStatus::ok);
  const Bytes good = image_of(set_b());
  for (std::size_t length = 0; length < good.size(); ++length) {
    put_file(storage.path(), Bytes(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(length)));
    const Loaded l = load(storage);
    ASSERT_EQ(l.report.source, can::LoadSource::previous) << "truncated to " << length << " bytes";
    ASSERT_EQ(l.report.current, can::ErrorCode::storage_corrupt) << "truncated to " << length << " bytes";
    ASSERT_EQ(l.image, image_of(set_a())) << "truncated to " << length << " bytes";
  }
  // One byte too many is as damaged as one too few.
  Bytes longer = good;
  longer.push_back(0);
  put_file(storage.path(), longer);
  EXPECT_EQ(load(storage).report.source, can::LoadSource::previous);
}

TEST(FileParamStorage, BothGenerationsDamagedLeaveTheDefaultsWholeAndReportIt) {
  const TempDir dir("both");
  drivers::FileParamStorage storage(dir.file("node.params"));
  ASSERT_EQ(storage.write(image_of(set_a())), hal::HalStatus::ok);
  ASSERT_EQ(storage.write(image_of(set_b())), hal::HalStatus::ok);
  Bytes bad_current = image_of(set_b());
  bad_current[20] ^= 0x01;
  put_file(storage.path(), bad_current);
  const Bytes a = image_of(set_a());
  put_file(storage.previous_path(), Bytes(a.begin(), a.end() - 3));
  const Loaded l = load(storage);
  EXPECT_EQ(l.report.source, can::LoadSource::neither);
  EXPECT_TRUE(l.report.fault());
  EXPECT_EQ(l.report.result(), can::ErrorCode::storage_corrupt);
  EXPECT_EQ(l.image, image_of(defaults())) << "not one parameter of either damaged set applied";
  // Only the previous one left, current deleted: the previous loads, as a fault.
  fs::remove(storage.path());
  put_file(storage.previous_path(), image_of(set_a()));
  const Loaded only_prev = load(storage);
  EXPECT_EQ(only_prev.report.source, can::LoadSource::previous);
  EXPECT_EQ(only_prev.image, image_of(set_a()));
}

TEST(FileParamStorage, AMissingDirectoryMeansNothingStoredAndIsCreatedByTheFirstSave) {
  const TempDir dir("missing");
  drivers::FileParamStorage storage((dir.path / "not" / "yet" / "node.params").string());
  std::array<std::uint8_t, can::kParamImageMaxBytes> buffer{};
  std::size_t size = 99;
  EXPECT_EQ(storage.read(buffer, size), hal::HalStatus::not_present);
  EXPECT_EQ(size, 0u);
  const Loaded l = load(storage);
  EXPECT_EQ(l.report.source, can::LoadSource::nothing_stored);
  EXPECT_FALSE(l.report.fault()) << "a node that never saved is not faulty";
  EXPECT_EQ(l.image, image_of(defaults()));
  ASSERT_EQ(storage.write(image_of(set_a())), hal::HalStatus::ok) << storage.last_error();
  EXPECT_EQ(load(storage).image, image_of(set_a()));
}

TEST(FileParamStorage, ADirectoryThatCannotBeCreatedRefusesTheSaveNamingIt) {
  const TempDir dir("blocked");
  put_file(dir.file("plain-file"), Bytes{1, 2, 3});
  drivers::FileParamStorage storage((dir.path / "plain-file" / "node.params").string());
  EXPECT_EQ(storage.write(image_of(set_a())), hal::HalStatus::bus_error);
  EXPECT_NE(storage.last_error().find("plain-file"), std::string::npos) << storage.last_error();
  EXPECT_EQ(file_bytes(dir.file("plain-file")), (Bytes{1, 2, 3})) << "nothing changed";
}

// The save into a read-only directory runs in a child; as root (which
// ignores permission bits) the child first becomes `nobody`.
TEST(FileParamStorage, AReadOnlyDirectoryRefusesTheSaveWithAClearErrorAndChangesNothing) {
  const TempDir dir("readonly");
  const std::string path = dir.file("node.params");
  {
    drivers::FileParamStorage storage(path);
    ASSERT_EQ(storage.write(image_of(set_a())), hal::HalStatus::ok);
    ASSERT_EQ(storage.write(image_of(set_b())), hal::HalStatus::ok);
  }
  ASSERT_EQ(::chmod(dir.path.c_str(), 0555), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    if (::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) ::_exit(3);
    drivers::FileParamStorage storage(path);
    const bool refused = storage.write(image_of(set_a())) != hal::HalStatus::ok;
    const bool named = storage.last_error().find(path) != std::string::npos &&
                       storage.last_error().find("ermission denied") != std::string::npos;
    ::_exit(refused ? (named ? 0 : 2) : 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_NE(WEXITSTATUS(status), 3) << "could not drop root to test permissions";
  EXPECT_NE(WEXITSTATUS(status), 1) << "the save into a read-only directory was accepted";
  EXPECT_NE(WEXITSTATUS(status), 2) << "the error does not name the file and the permission problem";
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(file_bytes(path), image_of(set_b())) << "current changed";
  EXPECT_EQ(file_bytes(path + ".prev"), image_of(set_a())) << "previous changed";
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

// The test: a child saves A, B, A, B, ... and is SIGKILLed after a
// random delay, 1000 times; after each kill the files must load as the old
// or the new set, bit-exact, from the current generation (never a fallback,
// never a mixture), and the previous generation must be one of them too.
TEST(FileParamStorage, AWriterKilledAtRandomPointsLeavesTheOldOrTheNewSetBitExact) {
  const TempDir dir("sigkill");
  const std::string path = dir.file("node.params");
  const Bytes a = image_of(set_a());
  const Bytes b = image_of(set_b());
  drivers::FileParamStorage storage(path);
  ASSERT_EQ(storage.write(a), hal::HalStatus::ok);
  // The kill delay spans a few saves, so kills land in every step of one.
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < 10; ++i) ASSERT_EQ(storage.write(i % 2 == 0 ? b : a), hal::HalStatus::ok);
  const auto save_us = std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - t0).count() / 10;
  std::mt19937 rng(20261121);
  std::uniform_int_distribution<long> delay_us(0, std::max<long>(3 * save_us, 200));
  // Which set a child saves first is drawn too: with a fixed first set, a
  // child that completes one save per life (slow forks, qemu) would leave
  // that set almost every time and the other would seldom be seen.
  std::bernoulli_distribution first_is_b(0.5);

  // Forking a sanitized process costs ~30 ms: the 1000 run in the Release build.
  constexpr int kKills = tnv::test::kSanitizedBuild ? 150 : 1000;
  int saw_a = 0, saw_b = 0, killed_mid_save = 0;
  for (int k = 0; k < kKills; ++k) {
    // The child says when its save loop starts, so the random delay counts
    // from there and not from fork(), whose cost varies (30 ms under ASan).
    int ready[2];
    ASSERT_EQ(::pipe(ready), 0);
    const unsigned first = first_is_b(rng) ? 0u : 1u;
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      ::close(ready[0]);
      drivers::FileParamStorage writer(path);
      const char go = 1;
      if (::write(ready[1], &go, 1) != 1) ::_exit(3);
      for (unsigned n = first;; ++n) writer.write((n % 2 == 0) ? b : a);
    }
    ::close(ready[1]);
    char go = 0;
    ASSERT_EQ(::read(ready[0], &go, 1), 1) << "kill " << k << ": the writer never started";
    ::close(ready[0]);
    const long us = delay_us(rng);
    if (us > 0) ::usleep(static_cast<useconds_t>(us));
    ::kill(child, SIGKILL);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status)) << "kill " << k;

    if (fs::exists(path + ".tmp")) ++killed_mid_save;
    const Bytes current = file_bytes(path);
    ASSERT_TRUE(current == a || current == b) << "kill " << k << ": current is neither set (" << current.size()
                                              << " bytes)";
    (current == a ? saw_a : saw_b) += 1;
    const Bytes previous = file_bytes(path + ".prev");
    ASSERT_TRUE(previous.empty() || previous == a || previous == b) << "kill " << k << ": previous is damaged";
    const Loaded l = load(storage);
    ASSERT_EQ(l.report.source, can::LoadSource::current) << "kill " << k;
    ASSERT_EQ(l.image, current) << "kill " << k << ": the loaded set is not the stored one";
  }
  // The kills really hit both sets and the middle of saves.
  EXPECT_GT(saw_a, kKills / 10);
  EXPECT_GT(saw_b, kKills / 10);
  EXPECT_GT(killed_mid_save, 0) << "no kill landed between writing the temp file and renaming it";
  RecordProperty("kills_mid_save", killed_mid_save);
  RecordProperty("kills_left_a", saw_a);
  RecordProperty("kills_left_b", saw_b);
  RecordProperty("save_us", static_cast<int>(save_us));
}

}  // namespace
}  // namespace tnv
