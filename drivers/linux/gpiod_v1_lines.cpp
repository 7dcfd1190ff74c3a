// BoardLines on the libgpiod v1 API (Debian 12: libgpiod 1.6.3).
#include <gpiod.h>
#include <time.h>

#include <cerrno>
#include <cstring>
#include <map>
#include <vector>

#include "drivers/linux/gpio_lines.hpp"

namespace tnv::drivers {

namespace {

constexpr const char* kConsumer = "tnv-fw";

class GpiodV1Lines final : public BoardLines {
 public:
  ~GpiodV1Lines() override {
    for (gpiod_line* line : requested_) gpiod_line_release(line);
    for (gpiod_line* line : found_by_name_) gpiod_line_close_chip(line);
    for (auto& [name, chip] : chips_) gpiod_chip_close(chip);
  }

  // nullptr line with `error` set on failure.
  gpiod_line* find(const LineSpec& spec, const char* key, std::string& error) {
    gpiod_line* line = nullptr;
    if (!spec.name.empty()) {
      line = gpiod_line_find(spec.name.c_str());
      if (line != nullptr) found_by_name_.push_back(line);
    } else {
      gpiod_chip* chip = chip_named(spec.chip);
      if (chip == nullptr) {
        error = describe_failure(key, spec, "no such GPIO chip");
        return nullptr;
      }
      line = gpiod_chip_get_line(chip, static_cast<unsigned>(spec.offset));
    }
    if (line == nullptr) error = describe_failure(key, spec, "no such GPIO line");
    return line;
  }

  bool request(gpiod_line* line, const LineSpec& spec, const char* key, int kind, std::string& error) {
    const int flags = spec.active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
    int r = -1;
    if (kind == 0) r = gpiod_line_request_input_flags(line, kConsumer, flags);
    if (kind == 1) r = gpiod_line_request_output_flags(line, kConsumer, flags, 0);
    if (kind == 2) r = gpiod_line_request_rising_edge_events_flags(line, kConsumer, flags);
    if (r != 0) {
      error = describe_failure(key, spec, "cannot request the line (in use, or no permission)");
      return false;
    }
    requested_.push_back(line);
    return true;
  }

  bool read_inputs(InputLevels& levels) noexcept override {
    bool ok = true;
    for (std::size_t i = 0; i < kInputLineCount; ++i) {
      levels.present[i] = inputs_[i] != nullptr;
      if (inputs_[i] == nullptr) continue;
      const int v = gpiod_line_get_value(inputs_[i]);
      if (v < 0) ok = false;
      levels.asserted[i] = v != 0;
    }
    return ok;
  }

  bool write_enables(bool x, bool y) noexcept override {
    bool ok = true;
    const bool values[kOutputLineCount] = {x, y};
    for (std::size_t i = 0; i < kOutputLineCount; ++i) {
      if (outputs_[i] != nullptr && gpiod_line_set_value(outputs_[i], values[i] ? 1 : 0) != 0) ok = false;
    }
    return ok;
  }

  bool has_tick() const noexcept override { return tick_ != nullptr; }

  TickEdge wait_tick(int timeout_ms, std::int64_t& edge_ns) noexcept override {
    if (tick_ == nullptr) return TickEdge::error;
    const timespec timeout{timeout_ms / 1000, static_cast<long>(timeout_ms % 1000) * 1'000'000L};
    for (;;) {
      const int r = gpiod_line_event_wait(tick_, &timeout);
      if (r == 0) return TickEdge::timeout;
      if (r < 0) return errno == EINTR ? TickEdge::timeout : TickEdge::error;
      gpiod_line_event event{};
      if (gpiod_line_event_read(tick_, &event) != 0) return TickEdge::error;
      if (event.event_type != GPIOD_LINE_EVENT_RISING_EDGE) continue;
      edge_ns = static_cast<std::int64_t>(event.ts.tv_sec) * 1'000'000'000 + event.ts.tv_nsec;
      return TickEdge::rising;
    }
  }

  std::array<gpiod_line*, kInputLineCount> inputs_{};
  std::array<gpiod_line*, kOutputLineCount> outputs_{};
  gpiod_line* tick_ = nullptr;

 private:
  gpiod_chip* chip_named(const std::string& name) {
    if (const auto it = chips_.find(name); it != chips_.end()) return it->second;
    gpiod_chip* chip = gpiod_chip_open_lookup(name.c_str());
    if (chip != nullptr) chips_.emplace(name, chip);
    return chip;
  }

  static std::string describe_failure(const char* key, const LineSpec& spec, const char* what) {
    std::string message = "lines.";
    message.append(key).append(" (").append(spec.describe()).append("): ").append(what);
    if (errno != 0) message.append(": ").append(std::strerror(errno));
    return message;
  }

  std::map<std::string, gpiod_chip*> chips_;
  std::vector<gpiod_line*> found_by_name_;
  std::vector<gpiod_line*> requested_;
};

}  // namespace

std::unique_ptr<BoardLines> open_board_lines(const LineConfig& config, std::string& error) {
  if (!config.any()) return nullptr;
  auto lines = std::make_unique<GpiodV1Lines>();
  auto take = [&](const LineSpec& spec, const char* key, int kind, gpiod_line*& slot) {
    if (!spec.configured()) return true;
    errno = 0;
    gpiod_line* line = lines->find(spec, key, error);
    if (line == nullptr || !lines->request(line, spec, key, kind, error)) return false;
    slot = line;
    return true;
  };
  if (!take(config.tick, "tick", 2, lines->tick_)) return nullptr;
  for (std::size_t i = 0; i < kInputLineCount; ++i) {
    if (!take(config.inputs[i], line_key(static_cast<InputLine>(i)), 0, lines->inputs_[i])) return nullptr;
  }
  for (std::size_t i = 0; i < kOutputLineCount; ++i) {
    if (!take(config.outputs[i], line_key(static_cast<OutputLine>(i)), 1, lines->outputs_[i])) return nullptr;
  }
  return lines;
}

const char* gpio_backend() noexcept { return "libgpiod v1"; }

}  // namespace tnv::drivers
