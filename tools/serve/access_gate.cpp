#include "tools/serve/access_gate.hpp"

#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "tools/serve/api_error.hpp"
// Last: <resolv.h>, which it includes, defines the macro _res that Eigen's headers use as a name.
#include <httplib.h>

namespace tnv::serve {

namespace {

constexpr std::size_t kSecretBytes = 32;
constexpr std::size_t kMinSecretChars = 32;
constexpr int kHttpUnauthorized = 401;
constexpr int kHttpPayloadTooLarge = 413;
constexpr int kHttpUnsupportedMediaType = 415;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

bool secret_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '.' || c == '_' || c == '~' || c == '-';
}

std::string hex(const unsigned char* bytes, std::size_t n) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string s;
  for (std::size_t i = 0; i < n; ++i) {
    s.push_back(kDigits[bytes[i] >> 4]);
    s.push_back(kDigits[bytes[i] & 0xF]);
  }
  return s;
}

}  // namespace

bool loopback_host(const std::string& host) {
  if (host == "localhost" || host == "::1") return true;
  // 127.0.0.0/8 as a dotted quad of four decimal bytes.
  unsigned a = 0, b = 0, c = 0, d = 0;
  char tail = 0;
  if (std::sscanf(host.c_str(), "%3u.%3u.%3u.%3u%c", &a, &b, &c, &d, &tail) != 4) return false;
  return a == 127 && b < 256 && c < 256 && d < 256 &&
         host.find_first_not_of("0123456789.") == std::string::npos;
}

std::string bind_refusal(const std::string& bind, const std::string& tls_cert, const std::string& tls_key) {
  if (tls_cert.empty() != tls_key.empty()) return "TLS needs both --tls-cert and --tls-key";
  if (!loopback_host(bind) && tls_cert.empty())
    return "--bind " + bind +
           " would open the page to the network without encryption: give --tls-cert and --tls-key too, "
           "or keep the default --bind 127.0.0.1";
  return "";
}

namespace {

bool state_changing(const std::string& method) { return method != "GET" && method != "HEAD"; }

bool api_path(const std::string& path) { return path == "/api" || path.rfind("/api/", 0) == 0; }

// Content-Length as a number; a malformed one counts as over any cap.
std::size_t declared_length(const httplib::Request& req) {
  if (!req.has_header("Content-Length")) return 0;
  const std::string v = trimmed(req.get_header_value("Content-Length"));
  if (v.empty() || v.size() > 18 || v.find_first_not_of("0123456789") != std::string::npos)
    return static_cast<std::size_t>(-1);
  return static_cast<std::size_t>(std::stoull(v));
}

GateVerdict refuse(int status, std::string reason, std::string session = "") {
  return {status, std::move(reason), std::move(session)};
}

}  // namespace

std::string make_secret() {
  unsigned char bytes[kSecretBytes];
  std::size_t got = 0;
  while (got < sizeof bytes) {
    const ssize_t n = ::getrandom(bytes + got, sizeof bytes - got, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error(std::string("cannot make the page's secret: getrandom: ") + std::strerror(errno));
    got += static_cast<std::size_t>(n);
  }
  return hex(bytes, sizeof bytes);
}

std::string read_secret_file(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw std::runtime_error("token file " + path + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw std::runtime_error("token file " + path + " is not a regular file");
  if (st.st_uid != ::geteuid())
    throw std::runtime_error("token file " + path + " belongs to another user: refused (a secret is its owner's)");
  if ((st.st_mode & (S_IRWXG | S_IRWXO)) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%03o", static_cast<unsigned>(st.st_mode & 0777));
    throw std::runtime_error("token file " + path + " has mode " + mode +
                             ": others may read or change it; refused (chmod 600 " + path + ")");
  }
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw std::runtime_error("token file " + path + ": cannot read it");
  const std::string secret = trimmed(text.str());
  if (secret.size() < kMinSecretChars || !std::all_of(secret.begin(), secret.end(), secret_char))
    throw std::runtime_error("token file " + path + ": the secret must be at least " + std::to_string(kMinSecretChars) +
                             " characters of A-Z a-z 0-9 . _ ~ - on one line (e.g. `openssl rand -hex 32`)");
  return secret;
}

bool equal_in_constant_time(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char diff = 0;
  const volatile char* pa = a.data();
  const volatile char* pb = b.data();
  for (std::size_t i = 0; i < a.size(); ++i) diff = static_cast<unsigned char>(diff | (pa[i] ^ pb[i]));
  return diff == 0;
}

AccessGate::AccessGate(GateOptions options) : options_(std::move(options)) {
  if (options_.secret.size() < kMinSecretChars) throw std::invalid_argument("the page's secret is too short");
}

void AccessGate::set_port(int port) { options_.port = port; }

std::string AccessGate::host_of(const std::string& authority) {
  if (authority.empty()) return "";
  std::string host;
  std::string rest;
  if (authority.front() == '[') {  // [v6]:port
    const auto close = authority.find(']');
    if (close == std::string::npos) return "";
    host = authority.substr(1, close - 1);
    rest = authority.substr(close + 1);
  } else {
    const auto colon = authority.find(':');
    host = authority.substr(0, colon);
    rest = colon == std::string::npos ? "" : authority.substr(colon);
  }
  if (!rest.empty()) {
    if (rest.front() != ':' || rest.size() < 2 || rest.size() > 6 ||
        rest.find_first_not_of("0123456789", 1) != std::string::npos)
      return "";
  }
  if (host.empty() || host.find_first_of(" \t/@?#") != std::string::npos) return "";
  return lower(host);
}

bool AccessGate::host_allowed(const std::string& host) const {
  if (host.empty()) return false;
  if (loopback_host(host)) return true;
  const std::string bind = lower(options_.bind);
  return bind != "0.0.0.0" && bind != "::" && host == bind;
}

std::size_t AccessGate::body_limit(const std::string& path) const {
  return path.rfind("/api/program/", 0) == 0 ? options_.max_program_bytes : options_.max_body_bytes;
}

std::string AccessGate::origin() const {
  return std::string(options_.tls ? "https" : "http") + "://127.0.0.1:" + std::to_string(options_.port);
}

std::string AccessGate::cookie_name() const { return "tnv_session_" + std::to_string(options_.port); }

std::string AccessGate::set_cookie(const std::string& session_id) const {
  std::string c = cookie_name() + "=" + session_id + "; Path=/; HttpOnly; SameSite=Strict";
  if (options_.tls) c += "; Secure";
  return c;
}

std::string AccessGate::open_session(const std::string& token) {
  if (!equal_in_constant_time(token, options_.secret)) return "";
  const std::lock_guard lock(mutex_);
  sessions_.push_back({make_secret(), ++sessions_opened_});
  while (sessions_.size() > options_.max_sessions) sessions_.pop_front();
  return sessions_.back().id;
}

std::string AccessGate::cookie_session(const httplib::Request& req) const {
  const std::string prefix = cookie_name() + "=";
  // Every Cookie header, every "name=value" in it.
  const std::size_t headers = req.get_header_value_count("Cookie");
  for (std::size_t h = 0; h < headers; ++h) {
    std::stringstream cookies(req.get_header_value("Cookie", h));
    for (std::string part; std::getline(cookies, part, ';');) {
      part = trimmed(part);
      if (part.rfind(prefix, 0) != 0) continue;
      const std::string value = part.substr(prefix.size());
      const std::lock_guard lock(mutex_);
      std::string found;
      for (const Session& s : sessions_)  // every one compared: the time does not say which matched
        if (equal_in_constant_time(value, s.id)) found = "cookie#" + std::to_string(s.number);
      if (!found.empty()) return found;
    }
  }
  return "";
}

GateVerdict AccessGate::check(const httplib::Request& req) const {
  // Host first: a rebound name is refused whatever else it carries.
  if (!req.has_header("Host")) return refuse(kHttpForbidden, "no Host header");
  const std::string host = host_of(trimmed(req.get_header_value("Host")));
  if (!host_allowed(host))
    return refuse(kHttpForbidden, "Host '" + req.get_header_value("Host") +
                                      "' is not this server's: open the page as " + origin() + "/");
  if (!api_path(req.path) && !state_changing(req.method)) return {};  // the page's own files: no secret in them

  std::string session = cookie_session(req);
  if (session.empty() && req.has_header("Authorization")) {
    const std::string auth = req.get_header_value("Authorization");
    static constexpr const char kBearer[] = "Bearer ";
    if (auth.rfind(kBearer, 0) == 0 && equal_in_constant_time(trimmed(auth.substr(sizeof kBearer - 1)), options_.secret))
      session = "bearer";
  }
  if (session.empty())
    return refuse(kHttpUnauthorized,
                  "no valid session: open the URL tnvctl serve printed (with ?token=...), or send "
                  "'Authorization: Bearer SECRET'");
  if (!state_changing(req.method)) return {0, "", session};

  if (options_.read_only) return refuse(kHttpForbidden, "this server is read-only (tnvctl serve --read-only)", session);
  const std::string scheme = options_.tls ? "https://" : "http://";
  const std::string expected = lower(scheme + trimmed(req.get_header_value("Host")));
  if (!req.has_header("Origin") || lower(trimmed(req.get_header_value("Origin"))) != expected)
    return refuse(kHttpForbidden, "a command needs 'Origin: " + expected + "' (the page's own origin)", session);
  // The server checks before it reads the body: its size and presence are the headers' word
  // (cpp-httplib then reads at most Content-Length, and refuses more than the cap itself).
  const std::size_t length = std::max(req.body.size(), declared_length(req));
  if (const std::size_t limit = body_limit(req.path); length > limit)
    return refuse(kHttpPayloadTooLarge, "the request body is over " + std::to_string(limit) + " bytes", session);
  if (length > 0 || req.has_header("Transfer-Encoding")) {
    const std::string type = lower(trimmed(req.get_header_value("Content-Type")));
    if (trimmed(type.substr(0, type.find(';'))) != "application/json")
      return refuse(kHttpUnsupportedMediaType, "the request body must be application/json", session);
  }
  return {0, "", session};
}

}  // namespace tnv::serve
