#include "drivers/storage/file_param_storage.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <system_error>

#include "drivers/storage/regular_file.hpp"

namespace tnv::drivers {

namespace fs = std::filesystem;

namespace {

std::string errno_text(int err) { return std::error_code(err, std::generic_category()).message(); }

std::string describe(const std::string& file, const char* what, int err) {
  std::string s = file;
  s.append(": ").append(what).append(": ").append(errno_text(err));
  return s;
}

// Writes all of `bytes` to `fd` (short writes and EINTR retried).
bool write_all(int fd, std::span<const std::uint8_t> bytes) noexcept {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

// fsync of a directory, so a rename in it survives a power cut.
int sync_dir(const std::string& dir) noexcept {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return errno;
  const int err = ::fsync(fd) == 0 ? 0 : errno;
  ::close(fd);
  return err;
}

}  // namespace

FileParamStorage::FileParamStorage(std::string path) : path_(std::move(path)), previous_(*this) {}

hal::HalStatus FileParamStorage::fail(std::string message) noexcept {
  last_error_ = std::move(message);
  return hal::HalStatus::bus_error;
}

hal::HalStatus FileParamStorage::write(std::span<const std::uint8_t> image) noexcept {
  try {
    last_error_.clear();
    const fs::path target(path_);
    const std::string dir = target.has_parent_path() ? target.parent_path().string() : std::string(".");
    std::error_code ec;
    // A directory made here is the owner's only (the image is the machine's tuning).
    if (fs::create_directories(dir, ec) && !ec) fs::permissions(dir, fs::perms::owner_all, ec);
    if (ec) return fail(dir + ": cannot create the directory: " + ec.message());

    // 1. the new image, whole and on disk, under a name nobody loads;
    // created exclusively and without following links, so nothing planted
    // at "<path>.tmp" is written through. A regular file there is ours, left
    // by an interrupted write: removed first. Anything else is refused.
    const std::string tmp = path_ + ".tmp";
    struct stat stale {};
    if (::lstat(tmp.c_str(), &stale) == 0) {
      if (!S_ISREG(stale.st_mode))
        return fail(tmp + ": refused: " + (S_ISLNK(stale.st_mode) ? "a symbolic link" : "not a regular file") +
                    " where the temporary image goes; remove it");
      if (::unlink(tmp.c_str()) != 0) return fail(describe(tmp, "cannot remove the stale temporary image", errno));
    }
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (fd < 0) return fail(describe(tmp, "cannot create", errno));
    const bool written = write_all(fd, image);
    int err = written ? 0 : errno;
    if (written && ::fsync(fd) != 0) err = errno;
    if (::close(fd) != 0 && err == 0) err = errno;
    if (err != 0 || !written) {
      ::unlink(tmp.c_str());
      return fail(describe(tmp, "cannot write", err != 0 ? err : EIO));
    }

    // 2. the current image becomes the previous one; "<path>" stays in place
    struct stat st {};
    if (::lstat(path_.c_str(), &st) == 0) {
      const std::string prev_tmp = path_ + ".prev.tmp";
      ::unlink(prev_tmp.c_str());  // left over from an interrupted write, if any
      if (::link(path_.c_str(), prev_tmp.c_str()) != 0) {
        err = errno;
        ::unlink(tmp.c_str());
        return fail(describe(prev_tmp, "cannot keep the previous image", err));
      }
      if (::rename(prev_tmp.c_str(), previous_path().c_str()) != 0) {
        err = errno;
        ::unlink(prev_tmp.c_str());
        ::unlink(tmp.c_str());
        return fail(describe(previous_path(), "cannot keep the previous image", err));
      }
      if ((err = sync_dir(dir)) != 0) {
        ::unlink(tmp.c_str());
        return fail(describe(dir, "cannot sync the directory", err));
      }
    }

    // 3. the new image becomes the current one, atomically
    if (::rename(tmp.c_str(), path_.c_str()) != 0) {
      err = errno;
      ::unlink(tmp.c_str());
      return fail(describe(path_, "cannot replace", err));
    }
    if ((err = sync_dir(dir)) != 0) return fail(describe(dir, "cannot sync the directory", err));
    return hal::HalStatus::ok;
  } catch (...) {
    return fail(path_ + ": out of memory");
  }
}

hal::HalStatus FileParamStorage::read_file(const std::string& file, std::span<std::uint8_t> out,
                                           std::size_t& size) noexcept {
  try {
    last_error_.clear();
    size = 0;
    // Our own file in the state directory: a symlink there is not ours (refused).
    const RegularFile f = open_regular_file(file, out.size(), LinkPolicy::refuse);
    if (f.missing) return hal::HalStatus::not_present;
    if (f.fd < 0) return fail(f.error + " (not a parameter image)");
    const int fd = f.fd;
    std::size_t done = 0;
    for (;;) {
      if (done == out.size()) break;
      const ssize_t n = ::read(fd, out.data() + done, out.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        const int err = errno;
        ::close(fd);
        return fail(describe(file, "cannot read", err));
      }
      if (n == 0) break;
      done += static_cast<std::size_t>(n);
    }
    ::close(fd);
    size = done;
    return hal::HalStatus::ok;
  } catch (...) {
    return fail(file + ": out of memory");
  }
}

hal::HalStatus FileParamStorage::read(std::span<std::uint8_t> out, std::size_t& size) noexcept {
  return read_file(path_, out, size);
}

hal::HalStatus FileParamStorage::Previous::write(std::span<const std::uint8_t>) noexcept {
  return owner_.fail(owner_.previous_path() + ": the previous generation is written only by rotation");
}

hal::HalStatus FileParamStorage::Previous::read(std::span<std::uint8_t> out, std::size_t& size) noexcept {
  try {
    return owner_.read_file(owner_.previous_path(), out, size);
  } catch (...) {
    return hal::HalStatus::bus_error;
  }
}

}  // namespace tnv::drivers
