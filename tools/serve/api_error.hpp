#pragma once
// A request the server answers with an HTTP error: the status and the
// text the page shows (a refusal names its reason).
#include <stdexcept>
#include <string>

namespace tnv::serve {

class ApiError : public std::runtime_error {
 public:
  ApiError(int status, const std::string& message) : std::runtime_error(message), status_(status) {}
  int status() const noexcept { return status_; }

 private:
  int status_;
};

inline constexpr int kHttpBadRequest = 400;   // bad input: nothing was sent to the node
inline constexpr int kHttpForbidden = 403;    // this browser does not have control
inline constexpr int kHttpNotFound = 404;
inline constexpr int kHttpConflict = 409;     // the node refused (the reason says why)
inline constexpr int kHttpNotImplemented = 501;
inline constexpr int kHttpBadGateway = 502;   // the node did not answer, or the bus failed
inline constexpr int kHttpUnavailable = 503;  // too many requests waiting for the node

}  // namespace tnv::serve
