#pragma once
// hal::ParamStorage in one file, for the emulated node: a write goes to
// "<path>.tmp" first and is renamed over the old image, so a failed or
// interrupted save leaves the previous image whole. The directory is
// created on the first write.
#include <string>

#include "hal/param_storage.hpp"

namespace tnv::can_host {

class FileParamStorage final : public hal::ParamStorage {
 public:
  explicit FileParamStorage(std::string path) : path_(std::move(path)) {}

  hal::HalStatus write(std::span<const std::uint8_t> image) noexcept override;
  hal::HalStatus read(std::span<std::uint8_t> out, std::size_t& size) noexcept override;

  const std::string& path() const noexcept { return path_; }
  // Why the last call failed ("" after a success), for messages.
  const std::string& last_error() const noexcept { return last_error_; }

 private:
  std::string path_;
  std::string last_error_;
};

// $XDG_STATE_HOME/tnvctl/emu-node.params, or ~/.local/state/tnvctl/emu-node.params
// (XDG base directory spec); "emu-node.params" in the working directory when
// neither variable is set.
std::string default_emulated_storage_path();

}  // namespace tnv::can_host
