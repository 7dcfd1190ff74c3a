// Files the daemon touches are not followed where they must not be and are
// read only when they are regular files of sane size: a planted symlink at
// the save's temporary name, a FIFO or /dev/zero as a parameter image or a
// config (drivers/storage/regular_file.hpp, file_param_storage.cpp).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "drivers/storage/file_param_storage.hpp"
#include "drivers/storage/regular_file.hpp"

namespace tnv {
namespace {

namespace fs = std::filesystem;

struct StorageScratchDir {
  explicit StorageScratchDir(const std::string& name) {
    path = fs::temp_directory_path() / ("tnv_files_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~StorageScratchDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string file(const char* leaf) const { return (path / leaf).string(); }
  fs::path path;
};

std::string text_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(FileSafety, ASymlinkPlantedAtTheTemporaryNameIsRefusedAndItsTargetUntouched) {
  const StorageScratchDir dir("symlink_tmp");
  const std::string victim = dir.file("victim");
  std::ofstream(victim) << "keep me";
  drivers::FileParamStorage storage(dir.file("node.params"));
  fs::create_symlink(victim, storage.path() + ".tmp");
  const std::vector<std::uint8_t> image(32, 0x5A);
  EXPECT_NE(storage.write(image), hal::HalStatus::ok);
  EXPECT_NE(storage.last_error().find("symbolic link"), std::string::npos) << storage.last_error();
  EXPECT_EQ(text_of(victim), "keep me");
  EXPECT_FALSE(fs::exists(storage.path())) << "nothing saved";
}

TEST(FileSafety, AStaleTemporaryImageOfOursIsReplaced) {
  const StorageScratchDir dir("stale_tmp");
  drivers::FileParamStorage storage(dir.file("node.params"));
  std::ofstream(storage.path() + ".tmp") << "left by a killed save";
  const std::vector<std::uint8_t> image(32, 0x5A);
  ASSERT_EQ(storage.write(image), hal::HalStatus::ok) << storage.last_error();
  EXPECT_EQ(text_of(storage.path()), std::string(32, '\x5A'));
  EXPECT_FALSE(fs::exists(storage.path() + ".tmp"));
}

TEST(FileSafety, AFifoOrADeviceOrALinkAsTheParameterImageIsRefusedAtOnce) {
  const StorageScratchDir dir("fifo_params");
  std::array<std::uint8_t, 256> out{};
  std::size_t size = 0;
  {
    drivers::FileParamStorage storage(dir.file("fifo.params"));
    ASSERT_EQ(::mkfifo(storage.path().c_str(), 0600), 0);
    EXPECT_NE(storage.read(out, size), hal::HalStatus::ok) << "a FIFO with no writer must not hang the read";
    EXPECT_NE(storage.last_error().find("FIFO"), std::string::npos) << storage.last_error();
  }
  {
    drivers::FileParamStorage storage("/dev/zero");
    EXPECT_NE(storage.read(out, size), hal::HalStatus::ok);
    EXPECT_NE(storage.last_error().find("character device"), std::string::npos) << storage.last_error();
  }
  {
    drivers::FileParamStorage storage(dir.file("link.params"));
    std::ofstream(dir.file("real")) << "x";
    fs::create_symlink(dir.file("real"), storage.path());
    EXPECT_NE(storage.read(out, size), hal::HalStatus::ok);
    EXPECT_NE(storage.last_error().find("symbolic link"), std::string::npos) << storage.last_error();
  }
}

TEST(FileSafety, ReadRegularFileCapsTheSizeAndNamesTheType) {
  const StorageScratchDir dir("cap");
  std::string text, error;
  const std::string big = dir.file("big.toml");
  std::ofstream(big) << std::string(2000, 'x');
  EXPECT_FALSE(drivers::read_regular_file(big, 1000, drivers::LinkPolicy::follow, text, error));
  EXPECT_NE(error.find("2000 bytes, more than the 1000"), std::string::npos) << error;
  EXPECT_TRUE(drivers::read_regular_file(big, 2000, drivers::LinkPolicy::follow, text, error)) << error;
  EXPECT_EQ(text.size(), 2000u);
  EXPECT_FALSE(drivers::read_regular_file(dir.path.string(), 1000, drivers::LinkPolicy::follow, text, error));
  EXPECT_NE(error.find("a directory"), std::string::npos) << error;
  // A config may be a symlink by the administrator's choice.
  fs::create_symlink(big, dir.file("link.toml"));
  EXPECT_TRUE(drivers::read_regular_file(dir.file("link.toml"), 2000, drivers::LinkPolicy::follow, text, error)) << error;
  EXPECT_FALSE(drivers::read_regular_file(dir.file("link.toml"), 2000, drivers::LinkPolicy::refuse, text, error));
}

}  // namespace
}  // namespace tnv
