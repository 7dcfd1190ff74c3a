// The `unix:` CAN path: the node binds a socket there, replacing only a
// socket left by an earlier run; anything else at the path (a file, a
// symlink) is refused and left where it is.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "drivers/linux/unix_can_socket_api.hpp"

namespace tnv {
namespace {

namespace fs = std::filesystem;

std::string unix_can_scratch_path(const char* leaf) {
  return (fs::temp_directory_path() / ("tnv_unixcan_" + std::to_string(::getpid()) + "_" + leaf)).string();
}

TEST(UnixCanPath, ARegularFileAtThePathIsRefusedAndNotDeleted) {
  const std::string path = unix_can_scratch_path("file");
  std::ofstream(path) << "not a socket";
  drivers::UnixCanSocketApi api(path, drivers::UnixCanSocketApi::Role::node);
  const drivers::SysResult fd = api.open_can_raw();
  ASSERT_GE(fd.value, 0);
  const drivers::SysResult bound = api.bind_can(static_cast<int>(fd.value), 0);
  EXPECT_LT(bound.value, 0);
  EXPECT_EQ(bound.error, ENOTSOCK);
  api.close_fd(static_cast<int>(fd.value));
  EXPECT_TRUE(fs::is_regular_file(path)) << "tnv-fw must not unlink what is not its socket";
  fs::remove(path);
}

TEST(UnixCanPath, AStaleSocketIsReplacedAndRemovedOnClose) {
  const std::string path = unix_can_scratch_path("sock");
  for (int run = 0; run < 2; ++run) {  // the second run finds the first one's socket
    drivers::UnixCanSocketApi api(path, drivers::UnixCanSocketApi::Role::node);
    const drivers::SysResult fd = api.open_can_raw();
    ASSERT_GE(fd.value, 0);
    EXPECT_EQ(api.bind_can(static_cast<int>(fd.value), 0).value, 0) << "run " << run;
    EXPECT_TRUE(fs::is_socket(path));
    if (run == 1) {
      api.close_fd(static_cast<int>(fd.value));
      EXPECT_FALSE(fs::exists(path));
    } else {
      ::close(static_cast<int>(fd.value));  // killed: the socket file stays
    }
  }
}

}  // namespace
}  // namespace tnv
