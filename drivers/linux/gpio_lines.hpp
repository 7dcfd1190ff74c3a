#pragma once
// The I/O board's discrete lines on Linux GPIO (libgpiod): the tick line
// (rising edge wakes the control task), the e-stop, servo-alarm and limit
// inputs, and the servo-enable outputs. Each line is chosen by chip +
// offset or by line name. Which libgpiod API (v1 on Debian 12, v2 later)
// is used stays inside gpiod_v*_lines.cpp; without libgpiod the opener
// refuses any configured line with a clear message.
#include <array>
#include <cstdint>
#include <memory>
#include <string>

namespace tnv::drivers {

struct LineSpec {
  std::string chip;    // "gpiochip0" (with offset)
  int offset = -1;     // line offset on `chip`
  std::string name;    // or the line's name, searched on every chip
  bool active_low = false;
  bool configured() const noexcept { return offset >= 0 || !name.empty(); }
  std::string describe() const;  // "gpiochip0:4" or "TNV_ESTOP"
};

enum class InputLine : std::uint8_t { estop, alarm_x, alarm_y, limit_x_pos, limit_x_neg, limit_y_pos, limit_y_neg };
inline constexpr std::size_t kInputLineCount = 7;
enum class OutputLine : std::uint8_t { enable_x, enable_y };
inline constexpr std::size_t kOutputLineCount = 2;

// The config key of each line ("estop", "limit_x_pos", "enable_y", ...).
const char* line_key(InputLine line) noexcept;
const char* line_key(OutputLine line) noexcept;

struct LineConfig {
  LineSpec tick;
  std::array<LineSpec, kInputLineCount> inputs{};
  std::array<LineSpec, kOutputLineCount> outputs{};
  bool any() const noexcept;
};

// Levels read at one tick; `present` marks the configured lines.
struct InputLevels {
  std::array<bool, kInputLineCount> present{};
  std::array<bool, kInputLineCount> asserted{};  // logical level (active_low applied)
};

enum class TickEdge : std::uint8_t { rising, timeout, error };

class BoardLines {
 public:
  virtual ~BoardLines() = default;
  // One read of every configured input; false when a read failed.
  virtual bool read_inputs(InputLevels& levels) noexcept = 0;
  // Drives the configured enable outputs; false when a write failed.
  virtual bool write_enables(bool x, bool y) noexcept = 0;
  virtual bool has_tick() const noexcept = 0;
  // Waits for the tick line's next rising edge; edge_ns = the kernel's
  // CLOCK_MONOTONIC timestamp of the edge.
  virtual TickEdge wait_tick(int timeout_ms, std::int64_t& edge_ns) noexcept = 0;
};

// Requests every configured line (outputs start inactive = servo off);
// nullptr with a one-line error naming the line's key and spec.
std::unique_ptr<BoardLines> open_board_lines(const LineConfig& config, std::string& error);
// Whether this build can drive GPIO lines at all ("libgpiod 1.6.3" or "").
const char* gpio_backend() noexcept;

}  // namespace tnv::drivers
