#include "drivers/linux/unix_can_socket_api.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace tnv::drivers {

namespace {

sockaddr_un address_of(const std::string& path) {
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  std::strncpy(a.sun_path, path.c_str(), sizeof a.sun_path - 1);
  return a;
}

}  // namespace

std::string unix_can_path(const std::string& interface_name) {
  static constexpr char kPrefix[] = "unix:";
  if (interface_name.rfind(kPrefix, 0) != 0) return "";
  return interface_name.substr(sizeof kPrefix - 1);
}

SysResult UnixCanSocketApi::open_can_raw() { return result_of(::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0)); }

SysResult UnixCanSocketApi::interface_index(const std::string&) {
  if (path_.empty() || path_.size() >= sizeof(sockaddr_un::sun_path)) return {-1, ENAMETOOLONG};
  return {1, 0};
}

SysResult UnixCanSocketApi::set_filters(int, std::span<const can_filter> filters) {
  filters_.assign(filters.begin(), filters.end());
  return {0, 0};
}

SysResult UnixCanSocketApi::set_error_mask(int, can_err_mask_t mask) {
  error_mask_ = mask;
  return {0, 0};
}

SysResult UnixCanSocketApi::set_nonblocking(int fd) {
  const int flags = ::fcntl(fd, F_GETFL, 0);
  if (flags < 0) return {-1, errno};
  return result_of(::fcntl(fd, F_SETFL, flags | O_NONBLOCK));
}

SysResult UnixCanSocketApi::bind_can(int fd, int) {
  if (role_ == Role::node) {
    // Only a socket left by an earlier run is replaced; anything else at
    // the path (a file, a link, a directory) is not ours to delete.
    struct stat st {};
    if (::lstat(path_.c_str(), &st) == 0) {
      if (!S_ISSOCK(st.st_mode)) return {-1, ENOTSOCK};
      ::unlink(path_.c_str());
    }
    const sockaddr_un a = address_of(path_);
    if (::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) return {-1, errno};
    // Owner-only: connecting needs write permission on the socket, and only
    // this user's hosts may talk to the node (the daemon checked the directory).
    return result_of(::chmod(path_.c_str(), 0600));
  }
  // Host: autobind (an abstract name of the kernel's choosing) so the node can answer.
  sockaddr_un self{};
  self.sun_family = AF_UNIX;
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&self), sizeof(sa_family_t)) != 0) return {-1, errno};
  peer_ = address_of(path_);
  peer_len_ = sizeof peer_;
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&peer_), peer_len_) != 0) return {-1, errno};
  // An empty datagram joins the "bus": the node learns where to send before the host says anything.
  return result_of(::send(fd, nullptr, 0, MSG_NOSIGNAL));
}

SysResult UnixCanSocketApi::poll_one(int fd, short events, int timeout_ms) {
  pollfd p{fd, events, 0};
  const int n = ::poll(&p, 1, timeout_ms);
  if (n < 0) return {-1, errno};
  return {n == 0 ? 0 : static_cast<long>(p.revents), 0};
}

bool UnixCanSocketApi::passes(const can_frame& f) const noexcept {
  if ((f.can_id & CAN_ERR_FLAG) != 0) return (f.can_id & error_mask_ & CAN_ERR_MASK) != 0;
  for (const can_filter& k : filters_) {
    if ((f.can_id & k.can_mask) == (k.can_id & k.can_mask)) return true;
  }
  return false;
}

SysResult UnixCanSocketApi::read_some(int fd, void* buffer, std::size_t size) {
  for (;;) {
    can_frame f{};
    sockaddr_un from{};
    socklen_t from_len = sizeof from;
    const ssize_t n = ::recvfrom(fd, &f, sizeof f, 0, reinterpret_cast<sockaddr*>(&from), &from_len);
    if (n < 0) return {-1, errno};
    if (role_ == Role::node && from_len > sizeof(sa_family_t)) {
      peer_ = from;  // answer whoever spoke last
      peer_len_ = from_len;
    }
    if (n == 0) continue;  // a host joining
    if (static_cast<std::size_t>(n) == sizeof f && !passes(f)) continue;  // the kernel filter's job on CAN_RAW
    std::memcpy(buffer, &f, std::min(size, static_cast<std::size_t>(n)));
    return {static_cast<long>(n), 0};
  }
}

SysResult UnixCanSocketApi::write_some(int fd, const void* buffer, std::size_t size) {
  if (peer_len_ == 0) return {-1, ENOBUFS};  // nobody on the bus to acknowledge
  const ssize_t n = role_ == Role::host ? ::send(fd, buffer, size, MSG_NOSIGNAL)
                                        : ::sendto(fd, buffer, size, MSG_NOSIGNAL,
                                                   reinterpret_cast<const sockaddr*>(&peer_), peer_len_);
  if (n < 0 && (errno == ECONNREFUSED || errno == ENOENT)) {
    if (role_ == Role::node) peer_len_ = 0;  // the host went away
    return {-1, ENOBUFS};
  }
  return result_of(n);
}

void UnixCanSocketApi::close_fd(int fd) {
  ::close(fd);
  struct stat st {};
  if (role_ == Role::node && ::lstat(path_.c_str(), &st) == 0 && S_ISSOCK(st.st_mode)) ::unlink(path_.c_str());
}

Micros UnixCanSocketApi::monotonic_now() {
  return std::chrono::duration_cast<Micros>(std::chrono::steady_clock::now().time_since_epoch());
}

}  // namespace tnv::drivers
