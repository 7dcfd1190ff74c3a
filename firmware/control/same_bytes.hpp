#pragma once
// Byte-for-byte equality of two plain parameter structs (numbers, enums,
// fixed-size arrays and matrices: no pointers). Used to skip re-validating
// the part of a parameter set that did not change. Conservative by
// construction: equal bytes are equal values, so a skipped check would
// have passed again; padding that differs only costs a check that runs.
#include <cstring>
#include <type_traits>

namespace tnv::fw {

template <class T>
bool same_bytes(const T& a, const T& b) noexcept {
  static_assert(!std::is_pointer_v<T> && std::is_standard_layout_v<T>, "plain parameter structs only");
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

}  // namespace tnv::fw
