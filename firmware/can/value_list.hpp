#pragma once
// The value list of an enum field in the protocol's tables ("0=ok 1=busy"),
// made at compile time from the enum's own name list (the X-macro lists of
// fault.hpp, protocol_enums.hpp, tick_record.hpp), so a value added to an
// enum is in the DBC and the protocol document without a second edit.
#include <array>
#include <cstddef>

namespace tnv::fw::can {
namespace detail {

constexpr std::size_t decimal_digits(std::size_t v) {
  std::size_t n = 1;
  while (v >= 10) {
    v /= 10;
    ++n;
  }
  return n;
}

constexpr std::size_t name_chars(const char* name) {
  std::size_t n = 0;
  while (name[n] != '\0') ++n;
  return n;
}

template <const auto& Names>
constexpr std::size_t value_list_chars() {
  std::size_t n = 0;
  for (std::size_t i = 0; i < std::size(Names); ++i)
    n += (i > 0 ? 1 : 0) + decimal_digits(i) + 1 + name_chars(Names[i]);
  return n + 1;  // the terminating '\0'
}

template <const auto& Names>
constexpr std::array<char, value_list_chars<Names>()> make_value_list() {
  std::array<char, value_list_chars<Names>()> out{};
  std::size_t at = 0;
  for (std::size_t i = 0; i < std::size(Names); ++i) {
    if (i > 0) out[at++] = ' ';
    const std::size_t digits = decimal_digits(i);
    for (std::size_t d = 0, v = i; d < digits; ++d, v /= 10) out[at + digits - 1 - d] = static_cast<char>('0' + v % 10);
    at += digits;
    out[at++] = '=';
    for (const char* c = Names[i]; *c != '\0'; ++c) out[at++] = *c;
  }
  out[at] = '\0';
  return out;
}

template <const auto& Names>
inline constexpr auto kValueListText = make_value_list<Names>();

}  // namespace detail

// "0=<Names[0]> 1=<Names[1]> ...": Names is an array of the enum's names in
// value order (values 0, 1, 2, ... without gaps).
template <const auto& Names>
inline constexpr const char* kValueList = detail::kValueListText<Names>.data();

}  // namespace tnv::fw::can
