#pragma once
// One expansion for every enum written as a list (an X-macro: `#define
// TNV_THINGS(X) X(a) X(b) ...`, each entry a name and optionally more columns):
//
//   TNV_LISTED_ENUM(Thing, TNV_THINGS)
//
// declares, in the current namespace,
//   enum class Thing : std::uint8_t { a, b, ... };     values 0, 1, ... in list order
//   kThings      std::array of the values, in order
//   kThingNames  std::array of the names ("a", "b", ...), indexed by value
//   kThingCount  the number of entries (std::uint8_t)
//   to_string(Thing)  the name, "?" for a value outside the list
// so that a value added to the list is in all of them (and in the protocol's
// value lists made from the names, firmware/can/value_list.hpp). Further
// columns of an entry (X(name, ...)) are ignored here and read by the list's
// own extra tables. Shared by firmware/ and emulator/ (both may include hal/).
#include <array>
#include <cstddef>
#include <cstdint>

#define TNV_LISTED_ENUMERATOR(name, ...) name,
#define TNV_LISTED_NAME(name, ...) #name,

#define TNV_LISTED_ENUM(Type, LIST)                                                          \
  enum class Type : std::uint8_t { LIST(TNV_LISTED_ENUMERATOR) };                           \
  inline constexpr std::array k##Type##Names{LIST(TNV_LISTED_NAME)};                        \
  inline constexpr auto k##Type##Count = static_cast<std::uint8_t>(k##Type##Names.size()); \
  inline constexpr auto k##Type##s = [] {                                                   \
    std::array<Type, k##Type##Names.size()> values{};                                       \
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<Type>(i);       \
    return values;                                                                          \
  }();                                                                                      \
  constexpr const char* to_string(Type value) noexcept {                                    \
    const auto i = static_cast<std::size_t>(value);                                         \
    return i < k##Type##Names.size() ? k##Type##Names[i] : "?";                             \
  }
