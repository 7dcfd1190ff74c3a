#include "tools/gcode/canon_text_spool.hpp"

#include <array>
#include <cerrno>
#include <cstring>

namespace tnv::gcode {

namespace {

std::string why(int error_number) {
  std::string s = "cannot keep the calls in a temporary file: ";
  s += std::strerror(error_number);
  return s;
}

}  // namespace

CanonTextSpool::CanonTextSpool() : file_(std::tmpfile()) {
  if (!file_) errno_ = errno != 0 ? errno : EIO;
}

void CanonTextSpool::operator()(const CanonCall& call) {
  if (errno_ != 0) return;
  if (std::fwrite(call.text.data(), 1, call.text.size(), file_.get()) != call.text.size() ||
      std::fputc('\n', file_.get()) == EOF)
    errno_ = errno != 0 ? errno : EIO;
}

bool CanonTextSpool::ok(std::string& error) const {
  if (errno_ == 0) return true;
  error = why(errno_);
  return false;
}

bool CanonTextSpool::copy_to(std::ostream& out, std::string& error) {
  if (!ok(error)) return false;
  if (std::fflush(file_.get()) != 0 || std::fseek(file_.get(), 0, SEEK_SET) != 0) {
    error = why(errno != 0 ? errno : EIO);
    return false;
  }
  std::array<char, 1 << 16> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), file_.get())) > 0) {
    out.write(buffer.data(), static_cast<std::streamsize>(n));
    if (!out) {
      error = "cannot write the calls to the output";
      return false;
    }
  }
  if (std::ferror(file_.get()) != 0) {
    error = why(EIO);
    return false;
  }
  out.flush();
  return true;
}

}  // namespace tnv::gcode
