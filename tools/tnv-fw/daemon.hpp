#pragma once
// tnv-fw's runtime: the register transport and the FPGA board driver, the
// GPIO lines, the SocketCAN port, the parameter file, the firmware (tick
// task + CAN node) and the real-time loop that runs them, opened from a
// validated DaemonConfig. The controlling thread starts it, waits for a
// stop request (SIGTERM in main.cpp, a flag in tests) and stops it: the
// loop is joined first, then the outputs are made safe (DACs mid-scale,
// enables off) and read back from the board.
#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "drivers/fpga/fpga_io_board.hpp"
#include "drivers/linux/gpio_lines.hpp"
#include "drivers/linux/latency_histogram.hpp"
#include "drivers/linux/linux_io_board.hpp"
#include "drivers/linux/rt_loop.hpp"
#include "drivers/linux/socket_api.hpp"
#include "drivers/linux/socketcan_port.hpp"
#include "drivers/storage/file_param_storage.hpp"
#include "drivers/storage/thread_storage_worker.hpp"
#include "firmware/can/can_node.hpp"
#include "firmware/tick/tick_task.hpp"
#include "hal/axis.hpp"
#include "tools/tnv-fw/fw_config.hpp"

namespace tnv::fwd {

struct DaemonOptions {
  std::uint64_t max_ticks = 0;  // end the loop after this many ticks; 0 = until stopped
};

struct SafeStateReport {
  bool read_back = false;  // the output window could be read after the safe write
  std::array<std::uint32_t, hal::kAxisCount> dac{};  // each axis' DAC register, in the list's order
  std::uint32_t dac_spindle = 0, outputs = 0;
  bool safe = false;       // every DAC mid-scale (the spindle's too), every OUTPUTS bit off
  std::string one_line() const;
};

class Daemon {
 public:
  // Opens everything (board init included); nullptr with a one-line error.
  static std::unique_ptr<Daemon> open(const DaemonConfig& config, const DaemonOptions& options, std::string& error);
  ~Daemon();
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;

  // Starts the real-time loop; "" when running, else why not.
  std::string start();
  // The loop ended by itself (max_ticks reached or the tick source failed).
  bool finished() const noexcept { return loop_->finished(); }
  // Joins the loop, then outputs safe; idempotent.
  SafeStateReport stop();

  const std::string& warnings() const noexcept { return warnings_; }
  // Counters and latency, one line each: for the log at exit (the board
  // counters read 0 until stop()).
  std::string summary() const;
  drivers::RtLoopCounters loop_counters() const noexcept { return loop_->counters(); }
  drivers::CanPortCounters can_counters() const noexcept { return can_->counters(); }
  drivers::LatencySummary latency() const { return latency_.snapshot(); }

 private:
  Daemon() = default;
  bool cycle() noexcept;

  DaemonConfig config_;
  DaemonOptions options_;
  std::string warnings_;
  std::unique_ptr<hal::RegisterBus> bus_;
  std::unique_ptr<drivers::FpgaIoBoard> fpga_;
  std::unique_ptr<drivers::BoardLines> lines_;
  std::unique_ptr<drivers::LinuxIoBoard> board_;
  std::unique_ptr<drivers::SocketApi> own_socket_api_;
  std::unique_ptr<drivers::SocketCanPort> can_;
  std::unique_ptr<drivers::FileParamStorage> storage_;
  std::unique_ptr<fw::TickTask> task_;
  std::unique_ptr<fw::can::CanNode> node_;
  // Runs save/load for the node off the real-time thread. Declared after
  // the node and the storage: joined before either is destroyed.
  std::unique_ptr<drivers::ThreadStorageWorker> storage_worker_;
  std::unique_ptr<drivers::TickSource> tick_source_;
  drivers::LatencyHistogram latency_;
  std::unique_ptr<drivers::RtLoop> loop_;
  std::uint64_t ticks_ = 0;  // loop thread only
  bool stopped_ = false;
  SafeStateReport safe_{};
};

}  // namespace tnv::fwd
