#include "tools/serve/capture_shelf.hpp"

#include "tools/can/capture_csv.hpp"

namespace tnv::serve {

int CaptureShelf::add(can_host::CaptureTable table) {
  const std::lock_guard lock(mutex_);
  const int id = next_id_++;
  entries_.push_back({id, std::move(table)});
  while (entries_.size() > capacity_) entries_.pop_front();
  return id;
}

const CaptureShelf::Entry* CaptureShelf::find(int id) const {
  for (const Entry& e : entries_)
    if (e.id == id) return &e;
  return nullptr;
}

nlohmann::json CaptureShelf::list() const {
  const std::lock_guard lock(mutex_);
  nlohmann::json out = nlohmann::json::array();
  for (const Entry& e : entries_) {
    nlohmann::json names = nlohmann::json::array();
    for (const auto* c : e.table.channels) names.push_back(can_host::column_name(*c));
    out.push_back({{"id", e.id}, {"samples", e.table.samples()}, {"period_s", e.table.period_s()}, {"channels", names}});
  }
  return out;
}

std::optional<nlohmann::json> CaptureShelf::columns(int id) const {
  const std::lock_guard lock(mutex_);
  const Entry* e = find(id);
  if (e == nullptr) return std::nullopt;
  nlohmann::json t = nlohmann::json::array();
  for (std::size_t i = 0; i < e->table.samples(); ++i) t.push_back(static_cast<double>(i) * e->table.period_s());
  nlohmann::json cols = nlohmann::json::object();
  for (std::size_t c = 0; c < e->table.channels.size(); ++c)
    cols[can_host::column_name(*e->table.channels[c])] = e->table.columns[c];
  return nlohmann::json{{"id", id}, {"period_s", e->table.period_s()}, {"t_s", t}, {"columns", cols}};
}

std::optional<std::string> CaptureShelf::csv(int id) const {
  const std::lock_guard lock(mutex_);
  const Entry* e = find(id);
  if (e == nullptr) return std::nullopt;
  return can_host::capture_csv(e->table);
}

std::size_t CaptureShelf::size() const {
  const std::lock_guard lock(mutex_);
  return entries_.size();
}

}  // namespace tnv::serve
