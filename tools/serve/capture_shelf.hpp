#pragma once
// The captures taken from the page, newest last, at most `capacity` (the
// oldest is dropped): drawn as JSON columns and downloaded as the CSV
// `tnvctl capture --csv` writes.
#include <cstddef>
#include <deque>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "tools/can/capture_table.hpp"

namespace tnv::serve {

class CaptureShelf {
 public:
  explicit CaptureShelf(std::size_t capacity) : capacity_(capacity) {}

  // Keeps the table; returns its id (1, 2, ...).
  int add(can_host::CaptureTable table);
  // [{"id", "samples", "period_s", "channels": [...]}], oldest first.
  nlohmann::json list() const;
  // {"id", "period_s", "t_s": [...], "columns": {"pos_x_mm": [...], ...}}; nullopt if not kept.
  std::optional<nlohmann::json> columns(int id) const;
  std::optional<std::string> csv(int id) const;
  std::size_t size() const;

 private:
  struct Entry {
    int id;
    can_host::CaptureTable table;
  };
  const Entry* find(int id) const;  // mutex held
  mutable std::mutex mutex_;
  std::size_t capacity_;
  std::deque<Entry> entries_;
  int next_id_ = 1;
};

}  // namespace tnv::serve
