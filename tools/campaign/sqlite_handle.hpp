#pragma once
// The SQLite C API's handles closed by their owners, and a column name
// quoted for SQL ("plant.x.gain" holds dots): what merge and report share.
#include <string>

#include <sqlite3.h>

namespace tnv::campaign {

struct SqliteDb {
  sqlite3* db = nullptr;
  SqliteDb() = default;
  SqliteDb(const SqliteDb&) = delete;
  SqliteDb& operator=(const SqliteDb&) = delete;
  ~SqliteDb() { sqlite3_close(db); }
  // Runs `sql`; false with `error` set on failure.
  bool exec(const std::string& sql, std::string& error) {
    char* message = nullptr;
    if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &message) == SQLITE_OK) return true;
    error = std::string("sqlite: ") + (message != nullptr ? message : "error");
    sqlite3_free(message);
    return false;
  }
};

struct SqliteStatement {
  sqlite3_stmt* stmt = nullptr;
  SqliteStatement() = default;
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;
  ~SqliteStatement() { sqlite3_finalize(stmt); }
};

inline std::string quoted_identifier(const std::string& name) {
  std::string q = "\"";
  for (const char c : name) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace tnv::campaign
