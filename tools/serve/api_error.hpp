#pragma once
// A request the server answers with an HTTP error: the status and the
// text the page shows (a refusal names its reason).
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <utility>

namespace tnv::serve {

class ApiError : public std::runtime_error {
 public:
  ApiError(int status, const std::string& message, nlohmann::json detail = nullptr)
      : std::runtime_error(message), status_(status), detail_(std::move(detail)) {}
  int status() const noexcept { return status_; }
  // More fields of the answer beside "error" (a G-code refusal's line and column), or null.
  const nlohmann::json& detail() const noexcept { return detail_; }

 private:
  int status_;
  nlohmann::json detail_;
};

inline constexpr int kHttpBadRequest = 400;   // bad input: nothing was sent to the node
inline constexpr int kHttpForbidden = 403;    // this browser does not have control
inline constexpr int kHttpNotFound = 404;
inline constexpr int kHttpConflict = 409;     // the node refused (the reason says why)
inline constexpr int kHttpNotImplemented = 501;
inline constexpr int kHttpBadGateway = 502;   // the node did not answer, or the bus failed
inline constexpr int kHttpUnavailable = 503;  // too many requests waiting for the node

}  // namespace tnv::serve
