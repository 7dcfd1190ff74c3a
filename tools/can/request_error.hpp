#pragma once
// Why a request to a node did not succeed, with a message that names the
// request, the node and (for refusals) the ErrorCode and the parameter.
#include <stdexcept>
#include <string>

#include "firmware/can/protocol_enums.hpp"

namespace tnv::can_host {

class RequestError : public std::runtime_error {
 public:
  enum class Kind { timeout, refused, protocol };
  RequestError(Kind kind, const std::string& message, fw::can::ErrorCode code = fw::can::ErrorCode::ok)
      : std::runtime_error(message), kind_(kind), code_(code) {}
  Kind kind() const noexcept { return kind_; }
  fw::can::ErrorCode code() const noexcept { return code_; }

 private:
  Kind kind_;
  fw::can::ErrorCode code_;
};

}  // namespace tnv::can_host
