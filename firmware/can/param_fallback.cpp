#include "firmware/can/param_fallback.hpp"

#include <array>
#include <span>

#include "firmware/can/param_image.hpp"

namespace tnv::fw::can {
namespace {

constexpr ErrorCode kNotStored = ErrorCode::not_ready;  // internal: nothing under that generation

// One generation: not_ready when nothing is stored, else what decode_image()
// says; `generation` is the image's when it is intact (0 otherwise).
ErrorCode load_one(hal::ParamStorage& storage, NodeSettings& inout, std::uint32_t& generation) noexcept {
  std::array<std::uint8_t, kParamImageMaxBytes> buffer{};
  std::size_t size = 0;
  generation = 0;
  const hal::HalStatus st = storage.read(buffer, size);
  if (st == hal::HalStatus::not_present) return kNotStored;
  if (st != hal::HalStatus::ok || size > buffer.size()) return ErrorCode::storage_error;
  const std::span<const std::uint8_t> image(buffer.data(), size);
  if (!image_generation(image, generation)) generation = 0;
  return decode_image(image, inout);
}

}  // namespace

ErrorCode LoadReport::result() const noexcept {
  switch (source) {
    case LoadSource::current:
    case LoadSource::previous:
    case LoadSource::rolled_back: return ErrorCode::ok;
    case LoadSource::nothing_stored: return ErrorCode::not_ready;
    case LoadSource::neither: break;
  }
  return current != kNotStored ? current : previous;
}

LoadReport load_settings_with_fallback(hal::ParamStorage& current, hal::ParamStorage* previous,
                                       NodeSettings& inout) noexcept {
  LoadReport r;
  NodeSettings from_current = inout;
  r.current = load_one(current, from_current, r.current_generation);
  if (r.current == ErrorCode::ok) {
    // Intact current image: the previous one matters only if it is newer.
    NodeSettings from_previous = inout;
    if (previous != nullptr) {
      const ErrorCode p = load_one(*previous, from_previous, r.previous_generation);
      if (p == ErrorCode::ok && r.previous_generation > r.current_generation) {
        r.source = LoadSource::rolled_back;
        r.current = ErrorCode::storage_corrupt;  // the current image is not the newest save
        inout = from_previous;
        return r;
      }
    }
    r.source = LoadSource::current;
    inout = from_current;
    return r;
  }
  r.previous = previous != nullptr ? load_one(*previous, inout, r.previous_generation) : kNotStored;
  if (r.previous == ErrorCode::ok) {
    r.source = LoadSource::previous;
  } else if (r.current == kNotStored && r.previous == kNotStored) {
    r.source = LoadSource::nothing_stored;
    r.current = r.previous = ErrorCode::ok;
  } else {
    r.source = LoadSource::neither;
  }
  return r;
}

const char* to_string(LoadSource source) noexcept {
  switch (source) {
    case LoadSource::nothing_stored: return "nothing stored";
    case LoadSource::current: return "current";
    case LoadSource::previous: return "previous";
    case LoadSource::neither: return "neither";
    case LoadSource::rolled_back: return "previous (the current image is an older generation)";
  }
  return "?";
}

}  // namespace tnv::fw::can
