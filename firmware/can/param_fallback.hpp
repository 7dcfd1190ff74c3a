#pragma once
// Loading the stored parameters from two generations (the current image and
// the one saved before it): the current one when it decodes, else the
// previous one, else nothing (the caller's set stays, normally the
// defaults). Each image is checked whole by decode_image() (magic, version,
// length, CRC, every value, validate()), so a set is applied entirely or
// not at all. Using the previous generation or neither is a storage fault
// the node reports (HEARTBEAT.errors storage_fault).
// Rollback: each save stamps its image with one more than the generation
// it replaced (param_image.hpp). When both images are intact and the
// current one is OLDER than the previous one (files swapped, or an old
// copy restored over the current one), the newer one is loaded and the
// load is reported as `rolled_back`, a storage fault. Equal generations are
// normal: a save interrupted between keeping the old file as the previous
// generation and renaming the new one leaves the same image in both.
// No allocation, no exceptions; file or flash I/O through hal::ParamStorage.
#include <cstdint>

#include "firmware/can/node_settings.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "hal/param_storage.hpp"

namespace tnv::fw::can {

enum class LoadSource : std::uint8_t {
  nothing_stored,  // neither generation exists: `inout` unchanged, not a fault
  current,         // the current image
  previous,        // the current image is damaged or missing: the previous one
  neither,         // both damaged: `inout` unchanged
  rolled_back,     // both intact, the current one older: the previous (newer) one
};

struct LoadReport {
  LoadSource source = LoadSource::nothing_stored;
  // Why each generation was not used: ok when it was (or was not needed),
  // not_ready when nothing is stored under it, else decode_image()'s or
  // storage_error. Both ok when nothing is stored at all.
  ErrorCode current = ErrorCode::ok;
  ErrorCode previous = ErrorCode::ok;
  std::uint32_t current_generation = 0;   // of each intact image, else 0
  std::uint32_t previous_generation = 0;
  bool fault() const noexcept {
    return source == LoadSource::previous || source == LoadSource::neither || source == LoadSource::rolled_back;
  }
  // The error to answer a load request with: ok when a set was loaded.
  ErrorCode result() const noexcept;
};

// `previous` may be nullptr (a backend with one generation).
LoadReport load_settings_with_fallback(hal::ParamStorage& current, hal::ParamStorage* previous,
                                       NodeSettings& inout) noexcept;

const char* to_string(LoadSource source) noexcept;

}  // namespace tnv::fw::can
