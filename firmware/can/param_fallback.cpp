#include "firmware/can/param_fallback.hpp"

#include <array>
#include <span>

#include "firmware/can/param_image.hpp"

namespace tnv::fw::can {
namespace {

constexpr ErrorCode kNotStored = ErrorCode::not_ready;  // internal: nothing under that generation

// One generation: not_ready when nothing is stored, else what decode_image() says.
ErrorCode load_one(hal::ParamStorage& storage, NodeSettings& inout) noexcept {
  std::array<std::uint8_t, kParamImageMaxBytes> buffer{};
  std::size_t size = 0;
  const hal::HalStatus st = storage.read(buffer, size);
  if (st == hal::HalStatus::not_present) return kNotStored;
  if (st != hal::HalStatus::ok || size > buffer.size()) return ErrorCode::storage_error;
  return decode_image(std::span<const std::uint8_t>(buffer.data(), size), inout);
}

}  // namespace

ErrorCode LoadReport::result() const noexcept {
  switch (source) {
    case LoadSource::current:
    case LoadSource::previous: return ErrorCode::ok;
    case LoadSource::nothing_stored: return ErrorCode::not_ready;
    case LoadSource::neither: break;
  }
  return current != kNotStored ? current : previous;
}

LoadReport load_settings_with_fallback(hal::ParamStorage& current, hal::ParamStorage* previous,
                                       NodeSettings& inout) noexcept {
  LoadReport r;
  r.current = load_one(current, inout);
  if (r.current == ErrorCode::ok) {
    r.source = LoadSource::current;
    return r;
  }
  r.previous = previous != nullptr ? load_one(*previous, inout) : kNotStored;
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
  }
  return "?";
}

}  // namespace tnv::fw::can
