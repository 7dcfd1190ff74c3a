#include "tools/serve/audit_log.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "tools/serve/http_reply.hpp"
// Last: <resolv.h>, which it includes, defines the macro _res that Eigen's headers use as a name.
#include <httplib.h>

namespace tnv::serve {

namespace {

constexpr std::size_t kMaxLoggedBody = 512;  // a line stays a line; the rest is counted, not kept

std::string utc_now() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[96];  // room for any int the format can print (-Wformat-truncation)
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday,
                tm.tm_hour, tm.tm_min, tm.tm_sec, static_cast<int>(ms));
  return buf;
}

// The body as JSON when it is JSON, else its first bytes as text.
nlohmann::json logged_body(const std::string& body) {
  if (body.empty()) return nullptr;
  if (body.size() <= kMaxLoggedBody) {
    nlohmann::json j = nlohmann::json::parse(body, nullptr, false);
    if (!j.is_discarded()) return j;
  }
  std::string head = body.substr(0, kMaxLoggedBody);
  if (body.size() > kMaxLoggedBody) head += "... (" + std::to_string(body.size()) + " bytes)";
  return head;
}

}  // namespace

AuditLog::AuditLog(const std::string& path) {
  if (path.empty()) {
    file_ = stderr;
    return;
  }
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0600);
  if (fd < 0) throw std::runtime_error("audit file " + path + ": " + std::strerror(errno));
  file_ = ::fdopen(fd, "a");
  if (file_ == nullptr) {
    ::close(fd);
    throw std::runtime_error("audit file " + path + ": " + std::strerror(errno));
  }
  owned_ = true;
}

AuditLog::~AuditLog() {
  if (owned_) std::fclose(file_);
}

void AuditLog::write(const std::string& line) {
  const std::lock_guard lock(mutex_);
  std::fputs(line.c_str(), file_);
  std::fputc('\n', file_);
  std::fflush(file_);  // a trail that stops at a crash must hold everything before it
  ++lines_;
}

std::size_t AuditLog::lines() const {
  const std::lock_guard lock(mutex_);
  return lines_;
}

void AuditLog::request(const httplib::Request& req, const httplib::Response& res, const std::string& session) {
  request(req, res, session, logged_body(req.body));
}

void AuditLog::request(const httplib::Request& req, const httplib::Response& res, const std::string& session,
                       const nlohmann::json& body) {
  nlohmann::json line = {{"time", utc_now()},
                         {"peer", req.remote_addr + ":" + std::to_string(req.remote_port)},
                         {"session", session.empty() ? nlohmann::json(nullptr) : nlohmann::json(session)},
                         {"tab", req.get_header_value(kTokenHeader).substr(0, 64)},
                         {"method", req.method},
                         {"path", req.path.substr(0, 256)},
                         {"body", body},
                         {"status", res.status}};
  nlohmann::json answer = logged_body(res.body);
  line["answer"] = std::move(answer);
  write(json_text(line));
}

void AuditLog::event(const std::string& what, const std::string& detail) {
  const nlohmann::json line = {{"time", utc_now()}, {"session", "server"}, {"event", what}, {"detail", detail}};
  write(json_text(line));
}

}  // namespace tnv::serve
