#include "tools/can/file_param_storage.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace tnv::can_host {

namespace fs = std::filesystem;

hal::HalStatus FileParamStorage::write(std::span<const std::uint8_t> image) noexcept {
  try {
    last_error_.clear();
    const fs::path target(path_);
    std::error_code ec;
    if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
    if (ec) {
      last_error_ = target.parent_path().string() + ": " + ec.message();
      return hal::HalStatus::bus_error;
    }
    const std::string tmp = path_ + ".tmp";
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      out.write(reinterpret_cast<const char*>(image.data()), static_cast<std::streamsize>(image.size()));
      out.close();
      if (!out) {
        last_error_ = tmp + ": cannot write";
        fs::remove(tmp, ec);
        return hal::HalStatus::bus_error;
      }
    }
    fs::rename(tmp, target, ec);
    if (ec) {
      last_error_ = path_ + ": " + ec.message();
      fs::remove(tmp, ec);
      return hal::HalStatus::bus_error;
    }
    return hal::HalStatus::ok;
  } catch (...) {
    last_error_ = path_ + ": out of memory";
    return hal::HalStatus::bus_error;
  }
}

hal::HalStatus FileParamStorage::read(std::span<std::uint8_t> out, std::size_t& size) noexcept {
  try {
    last_error_.clear();
    size = 0;
    std::error_code ec;
    if (!fs::exists(path_, ec)) return hal::HalStatus::not_present;
    std::ifstream in(path_, std::ios::binary);
    if (!in) {
      last_error_ = path_ + ": cannot read";
      return hal::HalStatus::bus_error;
    }
    const auto length = static_cast<std::size_t>(fs::file_size(path_, ec));
    if (ec || length > out.size()) {
      last_error_ = path_ + ": larger than any parameter image";
      return hal::HalStatus::bus_error;
    }
    in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(length));
    if (static_cast<std::size_t>(in.gcount()) != length) {
      last_error_ = path_ + ": short read";
      return hal::HalStatus::bus_error;
    }
    size = length;
    return hal::HalStatus::ok;
  } catch (...) {
    last_error_ = path_ + ": cannot read";
    return hal::HalStatus::bus_error;
  }
}

std::string default_emulated_storage_path() {
  fs::path dir;
  if (const char* state = std::getenv("XDG_STATE_HOME"); state != nullptr && state[0] == '/') {
    dir = fs::path(state) / "tnvctl";
  } else if (const char* home = std::getenv("HOME"); home != nullptr && home[0] != '\0') {
    dir = fs::path(home) / ".local" / "state" / "tnvctl";
  }
  return (dir / "emu-node.params").string();
}

}  // namespace tnv::can_host
