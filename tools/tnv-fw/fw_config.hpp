#pragma once
// tnv-fw's configuration file (TOML; docs/install-board.md lists every
// key, packaging/tnv-fw.toml is the default). Read whole and validated
// before anything is opened: a bad file gives one line naming the file,
// the line and the key, and the daemon exits with code 2.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "drivers/linux/gpio_lines.hpp"

namespace tnv::fwd {

struct BoardConfig {
  std::string transport;             // "socket" (board-emulator process) or "spidev" (FPGA over SPI)
  std::string path;                  // socket path or /dev/spidevB.C
  std::uint32_t spi_speed_hz = 10'000'000;  // spidev only
  int connect_timeout_ms = 5000;     // socket only: wait for the server to come up
  int reply_timeout_ms = 20;         // one register transfer
};

struct CanConfig {
  std::string interface_name = "can0";  // or "unix:/path" (CAN frames over a Unix datagram socket)
  std::uint8_t node_id = 1;             // 1..31; overrides the stored parameter image's id
};

struct RtConfig {
  int priority = 80;   // SCHED_FIFO 1..99; 0 = no real-time priority
  int cpu = -1;        // CPU to pin the control thread to; -1 = any
  bool require = true; // refuse to run without SCHED_FIFO / mlockall
};

// The only tick period the firmware runs at (fw::TickTask's control period).
// Other values parse (--latency-test measures any period) but the daemon
// and --check-config refuse them: daemon_run_error().
inline constexpr std::uint32_t kFirmwarePeriodUs = 1000;

// A config file is a few kB; anything past 1 MiB is not one (e.g. /dev/zero).
inline constexpr std::size_t kMaxConfigBytes = 1u << 20;

struct TickConfig {
  std::uint32_t period_us = 1000;  // board tick period (the FPGA's TICK_DIVIDER) and the deadline period
};

struct ParamsConfig {
  std::string file = "/var/lib/tnv-fw/params.bin";
};

// Local permissions no CAN frame can grant (docs/safety.md "Commissioning").
struct SafetyConfig {
  bool allow_commissioning = false;  // COMMAND enter_commissioning accepted; else refused not_permitted
};

struct DaemonConfig {
  BoardConfig board;
  CanConfig can;
  drivers::LineConfig lines;
  RtConfig rt;
  TickConfig tick;
  ParamsConfig params;
  SafetyConfig safety;
};

struct ConfigResult {
  std::optional<DaemonConfig> config;
  std::string error;  // "FILE:LINE: key: what is wrong" when config is empty
};

ConfigResult parse_daemon_config(std::string_view text, const std::string& source_name);
ConfigResult load_daemon_config(const std::string& path);

// Why the daemon cannot run with a parsed config ("" when it can): today
// only a tick period other than 1000 us (the controllers, trajectories and
// the supervisor's late-tick check are built for 1 ms; the first tick would
// latch late_tick).
std::string daemon_run_error(const DaemonConfig& config);

}  // namespace tnv::fwd
