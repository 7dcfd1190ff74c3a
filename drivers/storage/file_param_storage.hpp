#pragma once
// hal::ParamStorage in files, two generations: "<path>" holds the current
// image and "<path>.prev" the one before it, so a current image that is
// later found damaged still has a last good set behind it (the firmware's
// load_settings_with_fallback() reads previous() when current fails).
//
// A write never leaves a half-written file under either name:
//   1. the new image goes to "<path>.tmp", fsync;
//   2. the current image is hard-linked to "<path>.prev.tmp" and renamed
//      over "<path>.prev" (the old image keeps "<path>" all the while);
//   3. "<path>.tmp" is renamed over "<path>";
//   4. the directory is fsync'd after each rename.
// A process killed at any instant leaves "<path>" holding the old or the
// new image, whole. The storage keeps bytes only: magic, version and CRC
// are the firmware's (fw::can param_image), checked when the image is
// loaded. The directory is created on the first write.
//
// Not for the tick: every call does file I/O (the CAN service calls it on
// save/load requests only).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "hal/param_storage.hpp"

namespace tnv::drivers {

class FileParamStorage final : public hal::ParamStorage {
 public:
  explicit FileParamStorage(std::string path);
  FileParamStorage(const FileParamStorage&) = delete;
  FileParamStorage& operator=(const FileParamStorage&) = delete;

  // Rotates current -> previous, then the new image -> current (see above).
  // On failure "<path>" still holds the image it held before.
  hal::HalStatus write(std::span<const std::uint8_t> image) noexcept override;
  // The current image; not_present when "<path>" does not exist.
  hal::HalStatus read(std::span<std::uint8_t> out, std::size_t& size) noexcept override;

  // The generation before the current one, read-only (write() refuses).
  hal::ParamStorage& previous() noexcept { return previous_; }

  const std::string& path() const noexcept { return path_; }
  std::string previous_path() const { return path_ + ".prev"; }
  // Why the last call failed ("" after a success), naming the file, for messages.
  const std::string& last_error() const noexcept { return last_error_; }

 private:
  class Previous final : public hal::ParamStorage {
   public:
    explicit Previous(FileParamStorage& owner) noexcept : owner_(owner) {}
    hal::HalStatus write(std::span<const std::uint8_t> image) noexcept override;
    hal::HalStatus read(std::span<std::uint8_t> out, std::size_t& size) noexcept override;

   private:
    FileParamStorage& owner_;
  };

  hal::HalStatus read_file(const std::string& file, std::span<std::uint8_t> out, std::size_t& size) noexcept;
  hal::HalStatus fail(std::string message) noexcept;

  std::string path_;
  std::string last_error_;
  Previous previous_;
};

}  // namespace tnv::drivers
