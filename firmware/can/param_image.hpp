#pragma once
// The stored parameter image: what save_params writes and load_params (and
// the start-up load) reads, through hal::ParamStorage.
//
// Layout, little-endian:
//   magic      u32  kParamImageMagic
//   version    u16  kParamImageVersion
//   count      u16  number of entries
//   generation u32  one more than the image this save replaced (1 for the
//                   first): the loader tells a rolled-back or swapped pair
//                   of generations by it (param_fallback.hpp)
//   count x { id u16, value f64 }   every read_write parameter, table order
//   bore state      the boring planner's learned state, kBoreStateImageBytes
//                   (bore_state_image.hpp)
//   crc     u32  CRC-32 (IEEE 802.3, reflected, init/xorout 0xFFFFFFFF)
//                over every byte before it
// Values are the settings' doubles (an f32 parameter holds exactly the
// float it arrived as, an integer parameter an integer), so a round trip is
// exact. Decoding is all or nothing: a bad magic, version, length or CRC,
// an unknown or read-only id, a value outside its parameter's range, a
// learned state that is not plausible -> storage_corrupt; a set that fails
// validate() as a whole -> invalid; in all cases `inout` is untouched.
// Parameters missing from the image keep their value in `inout` (an image
// from before a parameter was added).
// Older versions still load: version 2 (no bore state: `inout`'s learned
// state is kept, at start-up the fresh one) and version 1 (no generation
// field either, an 8-byte header; generation 0).
// No allocation, no exceptions.
#include <cstddef>
#include <cstdint>
#include <span>

#include "firmware/can/bore_state_image.hpp"
#include "firmware/can/node_settings.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "hal/param_storage.hpp"

namespace tnv::fw::can {

inline constexpr std::uint32_t kParamImageMagic = 0x50564E54u;  // "TNVP" as bytes 54 4E 56 50
inline constexpr std::uint16_t kParamImageVersion = 3;
inline constexpr std::uint16_t kParamImageVersion2 = 2;  // before the bore state: still loaded
inline constexpr std::uint16_t kParamImageVersion1 = 1;  // before the generation field: still loaded
inline constexpr std::size_t kParamImageHeaderBytes = 12;
inline constexpr std::size_t kParamImageVersion1HeaderBytes = 8;
inline constexpr std::size_t kParamImageEntryBytes = 10;
inline constexpr std::size_t kParamImageCrcBytes = 4;
inline constexpr std::size_t kParamImageMaxEntries = 384;  // > the table's read_write parameters (tested; 295 with X, Y, Z)
inline constexpr std::size_t kParamImageMaxBytes =
    kParamImageHeaderBytes + kParamImageMaxEntries * kParamImageEntryBytes + kBoreStateImageBytes + kParamImageCrcBytes;

// CRC-32 (IEEE) of `bytes`.
std::uint32_t crc32(std::span<const std::uint8_t> bytes) noexcept;

// Writes the image of `settings` into `out`; returns its length, or 0 when
// `out` is too small (nothing useful written).
std::size_t encode_image(const NodeSettings& settings, std::span<std::uint8_t> out,
                         std::uint32_t generation = 1) noexcept;

// The generation of a whole, intact image (magic, version, length and CRC
// checked; the values are not): false for anything else.
bool image_generation(std::span<const std::uint8_t> image, std::uint32_t& generation) noexcept;

// The generation the next save into `storage` writes: one more than the
// intact image stored there now, else 1. Reads the storage (worker side).
std::uint32_t next_generation(hal::ParamStorage& storage) noexcept;

// Writes `generation` into an encoded image and re-seals its CRC.
void stamp_generation(std::span<std::uint8_t> image, std::uint32_t generation) noexcept;

// All or nothing (see above): ok, storage_corrupt or invalid.
ErrorCode decode_image(std::span<const std::uint8_t> image, NodeSettings& inout) noexcept;

// Start-up load (before the TickTask is built) and the load_params command:
// nothing stored -> ok with `inout` unchanged; a read error -> storage_error;
// otherwise decode_image().
ErrorCode load_settings(hal::ParamStorage& storage, NodeSettings& inout) noexcept;

// save_params: encode with next_generation(storage) and write; storage_error when the write fails.
ErrorCode save_settings(hal::ParamStorage& storage, const NodeSettings& settings) noexcept;

}  // namespace tnv::fw::can
