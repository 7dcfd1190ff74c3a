#pragma once
// Result of validating a parameter set. Never allocates: field and reason
// point at string literals. A controller applies a set only when ok.

namespace tnv::fw {

struct ParamCheck {
  bool ok = true;
  const char* field = "";   // the offending member, e.g. "q"
  const char* reason = "";  // why, e.g. "must satisfy 0 < q < 1"
};

constexpr ParamCheck param_ok() noexcept { return {}; }
constexpr ParamCheck param_error(const char* field, const char* reason) noexcept {
  return {false, field, reason};
}

}  // namespace tnv::fw
