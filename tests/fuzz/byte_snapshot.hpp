#pragma once
// The bytes of an object taken once and written back over it, in place.
// For the persistent fuzz harness: resetting a firmware object this way
// skips its constructor's work (shaper and ARSC design, zeroing buffers).
// Sound only for an object that owns no heap memory and points only at
// itself or at objects that outlive it at the same address; the object
// must not move between save() and restore().
#include <cstddef>
#include <cstring>
#include <vector>

namespace tnv::fuzz {

class ByteSnapshot {
 public:
  // The first `size` bytes of `object` as they are now.
  void save(const void* object, std::size_t size) {
    object_ = const_cast<void*>(object);
    const auto* from = static_cast<const unsigned char*>(object);
    bytes_.assign(from, from + size);
  }
  void restore() const { std::memcpy(object_, bytes_.data(), bytes_.size()); }

 private:
  void* object_ = nullptr;
  std::vector<unsigned char> bytes_;
};

}  // namespace tnv::fuzz
