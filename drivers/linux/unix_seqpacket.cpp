#include "drivers/linux/unix_seqpacket.hpp"

#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace tnv::drivers {

namespace {

bool make_address(const std::string& path, sockaddr_un& addr, std::string& error) {
  addr = sockaddr_un{};
  addr.sun_family = AF_UNIX;
  if (path.empty() || path.size() >= sizeof addr.sun_path) {
    error = path;
    error += ": socket path empty or too long";
    return false;
  }
  std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
  return true;
}

std::string failed(const std::string& path, const char* step, int e) {
  std::string message = path;
  message.append(": ").append(step).append(": ").append(std::strerror(e));
  return message;
}

}  // namespace

int listen_seqpacket(const std::string& path, std::string& error) {
  sockaddr_un addr;
  if (!make_address(path, addr, error)) return -1;
  const int fd = ::socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    error = failed(path, "socket", errno);
    return -1;
  }
  // Only a socket left by an earlier run is replaced; nothing else at the path is ours to delete.
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) {
    if (!S_ISSOCK(st.st_mode)) {
      error = path + ": refused: something other than a socket is there (remove it)";
      ::close(fd);
      return -1;
    }
    ::unlink(path.c_str());
  }
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0 || ::listen(fd, 2) != 0) {
    error = failed(path, "cannot listen", errno);
    ::close(fd);
    return -1;
  }
  return fd;
}

int connect_seqpacket(const std::string& path, int timeout_ms, std::string& error) {
  sockaddr_un addr;
  if (!make_address(path, addr, error)) return -1;
  int waited_ms = 0;
  for (;;) {
    const int fd = ::socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0);
    if (fd < 0) {
      error = failed(path, "socket", errno);
      return -1;
    }
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0) return fd;
    const int e = errno;
    ::close(fd);
    if ((e != ENOENT && e != ECONNREFUSED) || waited_ms >= timeout_ms) {
      error = failed(path, "cannot connect to the board", e);
      return -1;
    }
    const timespec pause{0, 20'000'000};
    ::nanosleep(&pause, nullptr);
    waited_ms += 20;
  }
}

int accept_seqpacket(int listen_fd) { return ::accept4(listen_fd, nullptr, nullptr, SOCK_CLOEXEC); }

}  // namespace tnv::drivers
