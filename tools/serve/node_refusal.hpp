#pragma once
// A node's refusal as the page's HTTP 409 with the reason text (the
// limiting parameter, the safety rule, the owner); other failures pass.
#include "tools/can/param_set.hpp"
#include "tools/can/request_error.hpp"
#include "tools/serve/api_error.hpp"

namespace tnv::serve {

template <typename F>
auto refusals_as_conflict(F&& f) {
  try {
    return f();
  } catch (const can_host::RequestError& e) {
    if (e.kind() == can_host::RequestError::Kind::refused) throw ApiError(kHttpConflict, e.what());
    throw;
  } catch (const can_host::ParamSetMismatch& e) {
    throw ApiError(kHttpConflict, e.what());
  }
}

}  // namespace tnv::serve
