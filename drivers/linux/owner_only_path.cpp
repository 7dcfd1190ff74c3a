#include "drivers/linux/owner_only_path.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace tnv::drivers {

std::string parent_directory(const std::string& path) {
  const std::filesystem::path p(path);
  return p.has_parent_path() ? p.parent_path().string() : std::string(".");
}

std::string unsafe_directory(const std::string& dir) {
  std::filesystem::path p(dir);
  struct stat st {};
  // A directory to be created: its nearest existing parent decides.
  while (::stat(p.c_str(), &st) != 0) {
    if (errno != ENOENT || !p.has_parent_path() || p.parent_path() == p) return dir + ": " + std::strerror(errno);
    p = p.parent_path();
  }
  if (!S_ISDIR(st.st_mode)) return p.string() + " is not a directory";
  if (st.st_uid != ::geteuid() && st.st_uid != 0)
    return p.string() + " belongs to another user (uid " + std::to_string(st.st_uid) + "): refused";
  const bool sticky = (st.st_mode & S_ISVTX) != 0;
  if ((st.st_mode & (S_IWGRP | S_IWOTH)) != 0 && !sticky) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%03o", static_cast<unsigned>(st.st_mode & 0777));
    return p.string() + " (mode " + mode +
           ") is writable by other users, who could replace what is in it: refused (chmod go-w, or another directory)";
  }
  return "";
}

}  // namespace tnv::drivers
