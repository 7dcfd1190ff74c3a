#include "drivers/storage/regular_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

namespace tnv::drivers {

namespace {

std::string open_errno_text(int err) { return std::error_code(err, std::generic_category()).message(); }

const char* type_name(mode_t mode) noexcept {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

RegularFile open_regular_file(const std::string& path, std::size_t max_bytes, LinkPolicy links) noexcept {
  RegularFile f;
  try {
    int flags = O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY;
    if (links == LinkPolicy::refuse) flags |= O_NOFOLLOW;
    const int fd = ::open(path.c_str(), flags);
    if (fd < 0) {
      const int err = errno;
      if (err == ENOENT || err == ENOTDIR) {
        f.missing = true;
      } else if (err == ELOOP && links == LinkPolicy::refuse) {
        f.error = path + ": refused: a symbolic link (this file is opened without following links)";
      } else {
        f.error = path + ": cannot open: " + open_errno_text(err);
      }
      return f;
    }
    struct stat st {};
    if (::fstat(fd, &st) != 0) {
      f.error = path + ": cannot stat: " + open_errno_text(errno);
      ::close(fd);
      return f;
    }
    if (!S_ISREG(st.st_mode)) {
      f.error = path + ": refused: " + type_name(st.st_mode) + ", not a regular file";
      ::close(fd);
      return f;
    }
    const auto size = static_cast<std::size_t>(st.st_size);
    if (st.st_size < 0 || size > max_bytes) {
      f.error = path + ": refused: " + std::to_string(st.st_size) + " bytes, more than the " +
                std::to_string(max_bytes) + " this file may have";
      ::close(fd);
      return f;
    }
    // Reads block normally from here (a regular file never waits anyway).
    (void)::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    f.fd = fd;
    f.size = size;
  } catch (...) {
    f.error = "out of memory";
  }
  return f;
}

bool read_regular_file(const std::string& path, std::size_t max_bytes, LinkPolicy links, std::string& text,
                       std::string& error) {
  RegularFile f = open_regular_file(path, max_bytes, links);
  if (f.fd < 0) {
    error = f.missing ? path + ": cannot open: " + open_errno_text(ENOENT) : f.error;
    return false;
  }
  text.clear();
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(f.fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      error = path + ": cannot read: " + open_errno_text(errno);
      ::close(f.fd);
      return false;
    }
    if (n == 0) break;
    // The file may grow after the check: the cap holds for what is read too.
    if (text.size() + static_cast<std::size_t>(n) > max_bytes) {
      error = path + ": refused: grew past the " + std::to_string(max_bytes) + " bytes this file may have";
      ::close(f.fd);
      return false;
    }
    text.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(f.fd);
  return true;
}

}  // namespace tnv::drivers
