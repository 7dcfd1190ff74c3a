#pragma once
// Non-volatile storage for the node's parameter image (one blob). The
// firmware builds and checks the image (magic, version, CRC); the backend
// only keeps bytes: a file on the emulated board, flash or a file on a
// Linux board. Called from the CAN service, never from the tick.
#include <cstddef>
#include <cstdint>
#include <span>

#include "hal/status.hpp"

namespace tnv::hal {

class ParamStorage {
 public:
  virtual ~ParamStorage() = default;
  // Replaces the stored image as a whole: after a failed write the old
  // image is still there (write-new-then-rename, or two flash banks).
  virtual HalStatus write(std::span<const std::uint8_t> image) noexcept = 0;
  // Copies the stored image into `out`; `size` is its length. not_present
  // when nothing was ever stored; a too-small `out` is an error.
  virtual HalStatus read(std::span<std::uint8_t> out, std::size_t& size) noexcept = 0;
};

}  // namespace tnv::hal
