#pragma once
// The axis names in messages: a choice ("x or y") and a wire value's name,
// from the axis list (hal/axis.hpp). Compile-time text, nothing allocated.
#include <array>
#include <cstddef>

#include "hal/axis.hpp"

namespace tnv::hal {

// The name of the axis with this index (a wire value, e.g. a fault event's
// axis), `otherwise` for anything that is no axis' index.
constexpr const char* axis_label_or(long long i, const char* otherwise) noexcept {
  return i >= 0 && static_cast<unsigned long long>(i) < kAxisCount ? kAxisNames[static_cast<std::size_t>(i)] : otherwise;
}

namespace detail {
// "x or y" (three axes: "x, y or z"), each name between `quote`s.
constexpr std::array<char, 96> axis_choice_text(char quote) {
  std::array<char, 96> out{};
  std::size_t at = 0;
  const auto put = [&out, &at](const char* t) {
    while (*t != '\0') out[at++] = *t++;
  };
  for (std::size_t i = 0; i < kAxisCount; ++i) {
    if (i > 0) put(i + 1 == kAxisCount ? " or " : ", ");
    if (quote != '\0') out[at++] = quote;
    put(kAxisNames[i]);
    if (quote != '\0') out[at++] = quote;
  }
  return out;
}
inline constexpr std::array<char, 96> kAxisChoiceText = axis_choice_text('\0');
inline constexpr std::array<char, 96> kQuotedAxisChoiceText = axis_choice_text('"');
}  // namespace detail

// The axes as a choice in a message: "x or y", and "\"x\" or \"y\"".
inline constexpr const char* kAxisChoices = detail::kAxisChoiceText.data();
inline constexpr const char* kQuotedAxisChoices = detail::kQuotedAxisChoiceText.data();

}  // namespace tnv::hal
