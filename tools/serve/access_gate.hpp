#pragma once
// Who may use the tuning page's server: every request is checked here
// before any handler runs. The Host header must name a loopback address or
// the bind address (DNS rebinding), the API and the telemetry stream need
// the start's secret (a session cookie, exchanged once for the secret in
// the printed URL, or `Authorization: Bearer SECRET`), and a state-changing
// request needs a matching Origin, a JSON body of bounded size and a
// server that is not read-only. Pure logic over httplib::Request: the
// server and the fuzz target feed it the same requests.
#include <cstddef>
#include <deque>
#include <mutex>
#include <string>

namespace httplib {
struct Request;
}  // namespace httplib

namespace tnv::serve {

// 32 bytes from getrandom(2) as 64 hex digits (256 bits).
std::string make_secret();
// The secret in `path` (surrounding whitespace dropped). Throws
// std::runtime_error naming the file when it is missing, not the caller's,
// readable or writable by group or others (chmod 600), or shorter than 32
// characters of [A-Za-z0-9._~-].
std::string read_secret_file(const std::string& path);

// localhost, 127.0.0.0/8 as a dotted quad, or ::1.
bool loopback_host(const std::string& host);
// Why `bind` (with TLS or without) may not be served, or "": an address
// other than the loopback needs TLS, and the cert and the key come together.
std::string bind_refusal(const std::string& bind, const std::string& tls_cert, const std::string& tls_key);

// Equal in time that depends on the lengths only, not on where they differ.
bool equal_in_constant_time(const std::string& a, const std::string& b);

struct GateVerdict {
  int status = 0;      // 0: let it through; else the HTTP status of the refusal
  std::string reason;  // the refusal's text
  std::string session;  // who asked: "cookie#N", "bearer" or "" (no session)
  bool ok() const { return status == 0; }
};

struct GateOptions {
  std::string secret;
  std::string bind = "127.0.0.1";
  int port = 0;
  bool tls = false;
  bool read_only = false;
  std::size_t max_body_bytes = 64 * 1024;
  std::size_t max_program_bytes = 4 * 1024 * 1024;  // the body limit of /api/program/* (a whole program)
  std::size_t max_sessions = 32;  // the oldest cookie session is forgotten past this
};

class AccessGate {
 public:
  explicit AccessGate(GateOptions options);
  void set_port(int port);  // once bound (port 0 = any free port)

  // The request's verdict. `state_changing`: a POST (commands, changes,
  // control). Order: Host (403), secret (401), read-only (403), Origin
  // (403), body type (415) and size (413).
  GateVerdict check(const httplib::Request& req) const;
  // The host part of a Host header or an Origin's authority, lower case,
  // IPv6 without brackets; "" when malformed.
  static std::string host_of(const std::string& authority);
  // A loopback name or address (localhost, 127.0.0.0/8, ::1) or the bind address.
  bool host_allowed(const std::string& host) const;

  // `GET /?token=SECRET`: a new session's cookie value when the secret is
  // right, else "". The page then holds the cookie only.
  std::string open_session(const std::string& token);
  // The cookie's name: one per port (a browser's cookies ignore the port).
  std::string cookie_name() const;
  // The Set-Cookie header's value for `session_id`.
  std::string set_cookie(const std::string& session_id) const;
  std::string origin() const;  // scheme://127.0.0.1:port as the page is opened
  bool read_only() const { return options_.read_only; }
  std::size_t max_body_bytes() const { return options_.max_body_bytes; }
  // The body limit of a request to `path`: max_program_bytes for /api/program/*, else max_body_bytes.
  std::size_t body_limit(const std::string& path) const;

 private:
  // "cookie#N" for a known session id in the Cookie header, else "".
  std::string cookie_session(const httplib::Request& req) const;
  GateOptions options_;
  mutable std::mutex mutex_;
  struct Session {
    std::string id;
    int number;
  };
  std::deque<Session> sessions_;
  int sessions_opened_ = 0;
};

}  // namespace tnv::serve
