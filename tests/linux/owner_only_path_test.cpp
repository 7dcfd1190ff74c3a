// The board's files and sockets: tnv-fw refuses a CAN socket or parameter
// directory another user can write, and what it creates is owner-only
// (the unix: socket 0600, a new parameter directory 0700, the image 0600).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

#include "drivers/linux/owner_only_path.hpp"
#include "drivers/linux/unix_can_socket_api.hpp"
#include "drivers/storage/file_param_storage.hpp"

namespace tnv {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const char* leaf) {
  const fs::path p = fs::temp_directory_path() / ("tnv_owner_only_" + std::to_string(::getpid()) + "_" + leaf);
  fs::remove_all(p);
  return p;
}

unsigned mode_of(const fs::path& p) {
  struct stat st {};
  EXPECT_EQ(::lstat(p.c_str(), &st), 0) << p;
  return st.st_mode & 07777;
}

TEST(OwnerOnlyPath, ADirectoryOthersCanWriteIsRefused) {
  const fs::path dir = scratch("open");
  fs::create_directories(dir);
  ::chmod(dir.c_str(), 0777);
  const std::string why = drivers::unsafe_directory(dir.string());
  EXPECT_NE(why.find("writable by other users"), std::string::npos) << why;
  EXPECT_NE(why.find("mode 777"), std::string::npos) << why;
  // A directory yet to be made inside it is judged by it.
  EXPECT_NE(drivers::unsafe_directory((dir / "a" / "b").string()), "");
  ::chmod(dir.c_str(), 0775);
  EXPECT_NE(drivers::unsafe_directory(dir.string()), "") << "group-writable was accepted";
  ::chmod(dir.c_str(), 0755);
  EXPECT_EQ(drivers::unsafe_directory(dir.string()), "");
  ::chmod(dir.c_str(), 01777);  // /tmp's mode: nobody removes another's entry
  EXPECT_EQ(drivers::unsafe_directory(dir.string()), "");
  fs::remove_all(dir);
}

TEST(OwnerOnlyPath, TheNodesCanSocketIsOwnerOnly) {
  const fs::path dir = scratch("sock");
  fs::create_directories(dir);
  const std::string path = (dir / "can.sock").string();
  drivers::UnixCanSocketApi api(path, drivers::UnixCanSocketApi::Role::node);
  const drivers::SysResult fd = api.open_can_raw();
  ASSERT_GE(fd.value, 0);
  ASSERT_EQ(api.bind_can(static_cast<int>(fd.value), 0).value, 0);
  EXPECT_EQ(mode_of(path) & 0777, 0600u) << "another user could connect to the node";
  api.close_fd(static_cast<int>(fd.value));
  fs::remove_all(dir);
}

TEST(OwnerOnlyPath, ANewParameterDirectoryAndImageAreOwnerOnly) {
  const fs::path dir = scratch("params");
  drivers::FileParamStorage storage((dir / "state" / "params.bin").string());
  const std::array<std::uint8_t, 16> image{1, 2, 3};
  ASSERT_EQ(storage.write(image), hal::HalStatus::ok) << storage.last_error();
  EXPECT_EQ(mode_of(dir / "state"), 0700u);
  EXPECT_EQ(mode_of(dir / "state" / "params.bin") & 0777, 0600u);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace tnv
