#include "tools/tnv-fw/daemon.hpp"

#include <cstdio>

#include "drivers/linux/owner_only_path.hpp"
#include "drivers/linux/socket_register_bus.hpp"
#include "drivers/linux/spidev_register_bus.hpp"
#include "drivers/linux/unix_can_socket_api.hpp"
#include "firmware/can/param_fallback.hpp"
#include "firmware/can/param_table.hpp"
#include "hal/io_board_registers.hpp"

namespace tnv::fwd {

namespace {

constexpr std::uint32_t kClocksPerUs = hal::kTimebaseHz / 1'000'000;

}  // namespace

std::string SafeStateReport::one_line() const {
  if (!read_back) return "outputs: safe state written, but the board did not answer the read-back";
  std::string line = std::string("outputs ") + (safe ? "safe" : "NOT SAFE") + ":";
  char part[96];
  for (const hal::Axis a : hal::kAxes) {
    std::snprintf(part, sizeof part, " DAC %s %u,", hal::axis_label(a), dac[hal::index(a)]);
    line += part;
  }
  std::snprintf(part, sizeof part, " DAC spindle %u (mid-scale %u), enables 0x%x", dac_spindle,
                1u << (hal::regs::kDacBits - 1), outputs);
  return line + part;
}

std::unique_ptr<Daemon> Daemon::open(const DaemonConfig& config, const DaemonOptions& options, std::string& error) {
  std::unique_ptr<Daemon> d(new Daemon());
  d->config_ = config;
  d->options_ = options;

  // Register transport and the board.
  if (config.board.transport == "socket") {
    d->bus_ = drivers::SocketRegisterBus::connect(config.board.path, config.board.connect_timeout_ms,
                                                  config.board.reply_timeout_ms, error);
  } else {
    d->bus_ = drivers::SpidevRegisterBus::open({config.board.path, config.board.spi_speed_hz}, error);
  }
  if (!d->bus_) return nullptr;
  d->fpga_ = std::make_unique<drivers::FpgaIoBoard>(*d->bus_);
  drivers::FpgaBoardSettings board_settings;
  board_settings.tick_divider_clocks = config.tick.period_us * kClocksPerUs;
  board_settings.watchdog_timeout_clocks = 3 * board_settings.tick_divider_clocks;
  if (const drivers::FpgaInitResult init = d->fpga_->init(board_settings); !init.ok()) {
    error = "board (";
    error.append(config.board.path).append("): ").append(init.message);
    return nullptr;
  }

  // GPIO lines (optional).
  if (config.lines.any()) {
    d->lines_ = drivers::open_board_lines(config.lines, error);
    if (!d->lines_) return nullptr;
  }
  d->board_ = std::make_unique<drivers::LinuxIoBoard>(*d->fpga_, d->lines_.get());

  // CAN.
  drivers::SocketApi* api = &drivers::linux_socket_api();
  if (const std::string path = drivers::unix_can_path(config.can.interface_name); !path.empty()) {
    if (const std::string why = drivers::unsafe_directory(drivers::parent_directory(path)); !why.empty()) {
      error = "CAN socket " + path + ": " + why;
      return nullptr;
    }
    d->own_socket_api_ = std::make_unique<drivers::UnixCanSocketApi>(path, drivers::UnixCanSocketApi::Role::node);
    api = d->own_socket_api_.get();
  }
  drivers::SocketCanPortOptions can_options;
  can_options.interface_name = config.can.interface_name;
  can_options.node_id = config.can.node_id;
  d->can_ = drivers::SocketCanPort::open(*api, can_options, error);
  if (!d->can_) return nullptr;

  // Parameters: defaults, then the stored image, then what the config fixes.
  if (const std::string why = drivers::unsafe_directory(drivers::parent_directory(config.params.file)); !why.empty()) {
    error = "parameter file " + config.params.file + ": " + why;
    return nullptr;
  }
  namespace can = fw::can;
  d->storage_ = std::make_unique<drivers::FileParamStorage>(config.params.file);
  can::NodeSettings settings = can::default_node_settings();
  const can::LoadReport loaded = can::load_settings_with_fallback(*d->storage_, &d->storage_->previous(), settings);
  if (loaded.fault()) {
    d->warnings_.append(config.params.file).append(": stored parameters not loaded (")
        .append(can::to_string(loaded.source)).append("); ");
  }
  settings.can.node_id = config.can.node_id;
  settings.firmware.supervisor.tick_period_clocks = board_settings.tick_divider_clocks;
  settings.firmware.supervisor.period_tolerance_clocks = board_settings.tick_divider_clocks / 2;
  if (const can::SettingsCheck check = can::validate(settings); !check.ok) {
    error = "parameters refused: ";
    error.append(check.section).append(": ").append(check.reason);
    return nullptr;
  }
  d->task_ = std::make_unique<fw::TickTask>(*d->board_, settings.firmware);
  d->storage_worker_ = std::make_unique<drivers::ThreadStorageWorker>();
  d->node_ = std::make_unique<can::CanNode>(*d->task_, *d->can_, *d->storage_, settings, loaded.fault(),
                                            &d->storage_->previous(), d->storage_worker_.get());
  d->node_->allow_commissioning(config.safety.allow_commissioning);

  // The tick: the board's tick line when wired, else absolute deadlines.
  const std::int64_t period_ns = static_cast<std::int64_t>(config.tick.period_us) * 1000;
  if (d->lines_ && d->lines_->has_tick()) {
    d->tick_source_ = std::make_unique<drivers::GpioTickSource>(*d->lines_, period_ns);
  } else {
    d->tick_source_ = std::make_unique<drivers::DeadlineTickSource>(drivers::linux_monotonic_clock(), period_ns);
  }
  Daemon* self = d.get();
  d->loop_ = std::make_unique<drivers::RtLoop>(*d->tick_source_, drivers::linux_monotonic_clock(),
                                               drivers::linux_rt_system(), d->latency_,
                                               [self]() noexcept { return self->cycle(); });
  return d;
}

Daemon::~Daemon() { stop(); }

bool Daemon::cycle() noexcept {
  task_->tick();
  node_->service();
  ++ticks_;
  return options_.max_ticks == 0 || ticks_ < options_.max_ticks;
}

std::string Daemon::start() {
  drivers::RtPolicy policy;
  policy.priority = config_.rt.priority;
  policy.cpu = config_.rt.cpu;
  policy.require = config_.rt.require;
  std::string error = loop_->start(policy);
  if (error.empty() && !loop_->warnings().empty()) {
    warnings_.append("running WITHOUT the real-time policy (rt.require = false): ").append(loop_->warnings());
  }
  return error;
}

SafeStateReport Daemon::stop() {
  if (stopped_ || !loop_) return safe_;
  stopped_ = true;
  loop_->stop();
  // The loop thread is joined: this thread owns the board now.
  board_->force_safe_outputs();
  std::array<std::uint32_t, hal::regs::kOutputWords> out{};
  safe_.read_back = bus_->read_block(hal::regs::kOutputFirst, out) == hal::HalStatus::ok;
  for (const hal::Axis a : hal::kAxes)
    safe_.dac[hal::index(a)] = out[hal::regs::axis_registers(a).dac - hal::regs::kOutputFirst];
  safe_.dac_spindle = out[hal::regs::kDacSpindle - hal::regs::kOutputFirst];
  safe_.outputs = out[hal::regs::kOutputs - hal::regs::kOutputFirst];
  const std::uint32_t mid = 1u << (hal::regs::kDacBits - 1);
  // Every OUTPUTS bit is an enable or the spindle's direction: all off.
  bool dacs_mid = true;
  for (const std::uint32_t code : safe_.dac) dacs_mid = dacs_mid && code == mid;
  safe_.safe = safe_.read_back && dacs_mid && safe_.dac_spindle == mid && safe_.outputs == 0;
  return safe_;
}

std::string Daemon::summary() const {
  const drivers::RtLoopCounters l = loop_->counters();
  const drivers::CanPortCounters c = can_->counters();
  // The task's own counters belong to the loop thread until it is joined.
  const fw::TickCounters t = stopped_ ? task_->counters() : fw::TickCounters{};
  char line[512];
  std::snprintf(line, sizeof line,
                "ticks %llu, overruns %llu (skipped %llu), board bus errors %llu, late ticks %llu; "
                "CAN rx %llu tx %llu tx dropped %llu error frames %llu bus-off %llu recovered %llu",
                static_cast<unsigned long long>(l.cycles), static_cast<unsigned long long>(l.overruns),
                static_cast<unsigned long long>(l.skipped_ticks), static_cast<unsigned long long>(t.bus_errors),
                static_cast<unsigned long long>(t.late_ticks), static_cast<unsigned long long>(c.rx_frames),
                static_cast<unsigned long long>(c.tx_frames), static_cast<unsigned long long>(c.tx_dropped),
                static_cast<unsigned long long>(c.rx_error_frames), static_cast<unsigned long long>(c.bus_off_events),
                static_cast<unsigned long long>(c.bus_off_recoveries));
  std::string out = line;
  out.append("\nwake-up latency: ").append(latency_.snapshot().one_line());
  return out;
}

}  // namespace tnv::fwd
