#pragma once
// Result of validating a parameter set. Never allocates: field and reason
// point at string literals. A controller applies a set only when ok.

namespace tnv::fw {

struct ParamCheck {
  bool ok = true;
  const char* field = "";   // the offending member, e.g. "q"
  const char* reason = "";  // why, e.g. "must satisfy 0 < q < 1"
  // The offending member itself, in the object validated (nullptr: none
  // named). Whoever knows where that object lives (the CAN node's parameter
  // table) tells the parameter from it, without reading the text.
  const void* member = nullptr;

  constexpr ParamCheck() noexcept = default;
  constexpr ParamCheck(bool is_ok, const char* field_name, const char* why, const void* at = nullptr) noexcept
      : ok(is_ok), field(field_name), reason(why), member(at) {}
};

constexpr ParamCheck param_ok() noexcept { return {}; }
constexpr ParamCheck param_error(const char* field, const char* reason) noexcept {
  return {false, field, reason};
}
constexpr ParamCheck param_error(const void* member, const char* field, const char* reason) noexcept {
  return {false, field, reason, member};
}

}  // namespace tnv::fw
