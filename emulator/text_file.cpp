#include "emulator/text_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace tnv::emu {

bool read_text_file(const std::string& path, std::size_t max_bytes, std::string& text, std::string& error) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) {
    error = path + ": cannot read file: " + std::strerror(errno);
    return false;
  }
  struct stat st {};
  const char* refusal = nullptr;
  if (::fstat(fd, &st) != 0) {
    refusal = "cannot stat";
  } else if (S_ISDIR(st.st_mode)) {
    refusal = "is a directory";
  } else if (!S_ISREG(st.st_mode)) {
    refusal = "not a regular file (a FIFO, device or socket)";
  }
  if (refusal != nullptr) {
    error = path + ": cannot read file: " + refusal;
    ::close(fd);
    return false;
  }
  if (st.st_size < 0 || static_cast<std::size_t>(st.st_size) > max_bytes) {
    error = path + ": cannot read file: " + std::to_string(st.st_size) + " bytes, more than the " +
            std::to_string(max_bytes) + " allowed";
    ::close(fd);
    return false;
  }
  (void)::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  text.clear();
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      error = path + ": cannot read file: " + std::strerror(errno);
      ::close(fd);
      return false;
    }
    if (n == 0) break;
    if (text.size() + static_cast<std::size_t>(n) > max_bytes) {
      error = path + ": cannot read file: grew past " + std::to_string(max_bytes) + " bytes";
      ::close(fd);
      return false;
    }
    text.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return true;
}

std::string one_line(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return out;
}

}  // namespace tnv::emu
