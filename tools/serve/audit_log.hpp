#pragma once
// The audit trail of the tuning page's server: one JSON line for every
// state-changing request, accepted or refused — when, from where, which
// session and tab, what was asked and what the server or the node
// answered. Appended to a file (--audit FILE) or written to stderr (the
// journal, under systemd).
#include <cstdio>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

namespace httplib {
struct Request;
struct Response;
}  // namespace httplib

namespace tnv::serve {

class AuditLog {
 public:
  // "" = stderr. Throws std::runtime_error naming the file when it cannot
  // be opened; a new file is made owner-only (0600).
  explicit AuditLog(const std::string& path = "");
  ~AuditLog();
  AuditLog(const AuditLog&) = delete;
  AuditLog& operator=(const AuditLog&) = delete;

  // One request and its answer; `session` as the gate named it.
  void request(const httplib::Request& req, const httplib::Response& res, const std::string& session);
  // The same with `body` logged in place of the request's own (a program's summary, not its text).
  void request(const httplib::Request& req, const httplib::Response& res, const std::string& session,
               const nlohmann::json& body);
  // An event of the server's own (the dead-man rule's stop).
  void event(const std::string& what, const std::string& detail);
  std::size_t lines() const;

 private:
  void write(const std::string& line);
  mutable std::mutex mutex_;
  std::FILE* file_ = nullptr;
  bool owned_ = false;
  std::size_t lines_ = 0;
};

}  // namespace tnv::serve
