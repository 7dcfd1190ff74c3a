#include "tools/tnv-fw/fw_config.hpp"

#include <toml++/toml.h>

#include <limits>

#include "drivers/storage/regular_file.hpp"
#include "firmware/can/can_id.hpp"
#include "emulator/toml_type_name.hpp"

namespace tnv::fwd {

namespace {

// Collects the first error; every check names the key and the line.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  bool failed() const noexcept { return !error_.empty(); }
  const std::string& error() const noexcept { return error_; }

  void fail(std::uint32_t line, const std::string& key, const std::string& what) {
    if (failed()) return;
    error_ = source_;
    error_.append(":").append(std::to_string(line == 0 ? 1 : line)).append(": ").append(key).append(": ").append(what);
  }
  void fail(const toml::node& node, const std::string& key, const std::string& what) {
    fail(node.source().begin.line, key, what);
  }

  // Refuses keys of `table` that are not in `known`.
  void only(const toml::table& table, const std::string& prefix, std::initializer_list<std::string_view> known) {
    for (const auto& [k, v] : table) {
      bool ok = false;
      for (const std::string_view name : known) ok = ok || k.str() == name;
      if (!ok) {
        std::string hint = "unknown key (known:";
        for (const std::string_view name : known) hint.append(" ").append(name);
        hint += ")";
        fail(v, prefix + std::string(k.str()), hint);
      }
    }
  }

  const toml::table* table(const toml::table& root, std::string_view name) {
    const toml::node* n = root.get(name);
    if (n == nullptr) return nullptr;
    if (!n->is_table()) {
      fail(*n, std::string(name), std::string("must be a table, not ") + emu::toml_type_name(*n));
      return nullptr;
    }
    return n->as_table();
  }

  void text(const toml::table& t, const std::string& prefix, std::string_view key, std::string& out) {
    const toml::node* n = t.get(key);
    if (n == nullptr) return;
    if (!n->is_string()) return fail(*n, prefix + std::string(key), std::string("must be a string, not ") + emu::toml_type_name(*n));
    out = n->as_string()->get();
    if (out.empty()) fail(*n, prefix + std::string(key), "must not be empty");
  }

  template <typename Int>
  void integer(const toml::table& t, const std::string& prefix, std::string_view key, std::int64_t lo, std::int64_t hi,
               Int& out) {
    const toml::node* n = t.get(key);
    if (n == nullptr) return;
    const std::string name = prefix + std::string(key);
    const std::string range = std::to_string(lo) + ".." + std::to_string(hi);
    if (!n->is_integer()) return fail(*n, name, "must be an integer " + range + ", not " + emu::toml_type_name(*n));
    const std::int64_t v = n->as_integer()->get();
    if (v < lo || v > hi) return fail(*n, name, "must be " + range + " (got " + std::to_string(v) + ")");
    out = static_cast<Int>(v);
  }

  void boolean(const toml::table& t, const std::string& prefix, std::string_view key, bool& out) {
    const toml::node* n = t.get(key);
    if (n == nullptr) return;
    if (!n->is_boolean()) return fail(*n, prefix + std::string(key), std::string("must be true or false, not ") + emu::toml_type_name(*n));
    out = n->as_boolean()->get();
  }

  void line(const toml::table& lines, std::string_view key, drivers::LineSpec& out) {
    const toml::node* n = lines.get(key);
    if (n == nullptr) return;
    const std::string name = "lines." + std::string(key);
    if (!n->is_table()) {
      return fail(*n, name, std::string("must be a table {chip = \"gpiochip0\", offset = N} or {name = \"LINE\"}, not ") +
                                emu::toml_type_name(*n));
    }
    const toml::table& t = *n->as_table();
    only(t, name + ".", {"chip", "offset", "name", "active_low"});
    text(t, name + ".", "chip", out.chip);
    text(t, name + ".", "name", out.name);
    integer(t, name + ".", "offset", 0, 511, out.offset);
    boolean(t, name + ".", "active_low", out.active_low);
    if (failed()) return;
    const bool by_offset = t.contains("chip") || t.contains("offset");
    if (by_offset && t.contains("name")) return fail(*n, name, "give either name or chip + offset, not both");
    if (!by_offset && !t.contains("name")) return fail(*n, name, "needs name, or chip and offset");
    if (by_offset && !(t.contains("chip") && t.contains("offset"))) return fail(*n, name, "needs both chip and offset");
  }

 private:
  std::string source_;
  std::string error_;
};

std::uint32_t line_of(const toml::table* t) { return t == nullptr ? 1 : t->source().begin.line; }

}  // namespace

ConfigResult parse_daemon_config(std::string_view text, const std::string& source_name) {
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    std::string message = source_name;
    std::string what(e.description());
    for (char& c : what) {
      if (c == '\n') c = ' ';
    }
    message.append(":").append(std::to_string(e.source().begin.line)).append(": TOML syntax: ").append(what);
    return {std::nullopt, message};
  }

  Reader r(source_name);
  DaemonConfig c;
  r.only(root, "", {"board", "can", "lines", "rt", "tick", "params", "safety"});

  const toml::table* board = r.table(root, "board");
  if (board != nullptr) {
    r.only(*board, "board.", {"transport", "path", "spi_speed_hz", "connect_timeout_ms", "reply_timeout_ms"});
    r.text(*board, "board.", "transport", c.board.transport);
    r.text(*board, "board.", "path", c.board.path);
    r.integer(*board, "board.", "spi_speed_hz", 1000, 100'000'000, c.board.spi_speed_hz);
    r.integer(*board, "board.", "connect_timeout_ms", 0, 600'000, c.board.connect_timeout_ms);
    r.integer(*board, "board.", "reply_timeout_ms", 1, 10'000, c.board.reply_timeout_ms);
  }
  if (!r.failed()) {
    if (c.board.transport.empty()) {
      r.fail(line_of(board), "board.transport", "missing (\"socket\" or \"spidev\")");
    } else if (c.board.transport != "socket" && c.board.transport != "spidev") {
      r.fail(*board->get("transport"), "board.transport",
             "must be \"socket\" or \"spidev\" (got \"" + c.board.transport + "\")");
    } else if (c.board.path.empty()) {
      r.fail(line_of(board), "board.path",
             c.board.transport == "socket" ? "missing (the board server's socket)" : "missing (e.g. /dev/spidev0.0)");
    } else if (c.board.transport == "socket" && board->contains("spi_speed_hz")) {
      r.fail(*board->get("spi_speed_hz"), "board.spi_speed_hz", "only for transport = \"spidev\"");
    }
  }

  if (const toml::table* can = r.table(root, "can"); can != nullptr) {
    r.only(*can, "can.", {"interface", "node_id"});
    r.text(*can, "can.", "interface", c.can.interface_name);
    r.integer(*can, "can.", "node_id", 1, tnv::fw::can::kMaxNodeId, c.can.node_id);
    if (!r.failed() && c.can.interface_name.rfind("unix:", 0) != 0 && c.can.interface_name.size() > 15) {
      r.fail(*can->get("interface"), "can.interface", "a network interface name has at most 15 characters");
    }
  }

  if (const toml::table* lines = r.table(root, "lines"); lines != nullptr) {
    std::initializer_list<std::string_view> keys = {"tick",        "estop",       "alarm_x",     "alarm_y",
                                                    "limit_x_pos", "limit_x_neg", "limit_y_pos", "limit_y_neg",
                                                    "enable_x",    "enable_y"};
    r.only(*lines, "lines.", keys);
    r.line(*lines, "tick", c.lines.tick);
    for (std::size_t i = 0; i < drivers::kInputLineCount; ++i) {
      r.line(*lines, drivers::line_key(static_cast<drivers::InputLine>(i)), c.lines.inputs[i]);
    }
    for (std::size_t i = 0; i < drivers::kOutputLineCount; ++i) {
      r.line(*lines, drivers::line_key(static_cast<drivers::OutputLine>(i)), c.lines.outputs[i]);
    }
  }

  if (const toml::table* rt = r.table(root, "rt"); rt != nullptr) {
    r.only(*rt, "rt.", {"priority", "cpu", "require"});
    r.integer(*rt, "rt.", "priority", 0, 99, c.rt.priority);
    r.integer(*rt, "rt.", "cpu", -1, 1023, c.rt.cpu);
    r.boolean(*rt, "rt.", "require", c.rt.require);
  }

  if (const toml::table* tick = r.table(root, "tick"); tick != nullptr) {
    r.only(*tick, "tick.", {"period_us"});
    r.integer(*tick, "tick.", "period_us", 100, 100'000, c.tick.period_us);
  }

  if (const toml::table* params = r.table(root, "params"); params != nullptr) {
    r.only(*params, "params.", {"file"});
    r.text(*params, "params.", "file", c.params.file);
  }

  if (const toml::table* safety = r.table(root, "safety"); safety != nullptr) {
    r.only(*safety, "safety.", {"allow_commissioning"});
    r.boolean(*safety, "safety.", "allow_commissioning", c.safety.allow_commissioning);
  }

  if (r.failed()) return {std::nullopt, r.error()};
  return {c, ""};
}

ConfigResult load_daemon_config(const std::string& path) {
  // A config may be a symlink by the administrator's choice (e.g. to a
  // per-machine file); it must still be a regular file of sane size.
  std::string text, error;
  if (!drivers::read_regular_file(path, kMaxConfigBytes, drivers::LinkPolicy::follow, text, error))
    return {std::nullopt, error};
  return parse_daemon_config(text, path);
}

std::string daemon_run_error(const DaemonConfig& config) {
  if (config.tick.period_us != kFirmwarePeriodUs) {
    return "tick.period_us: must be 1000 to run the firmware: its models, trajectories and late-tick check are built "
           "for a 1 ms tick (got " +
           std::to_string(config.tick.period_us) + "; other periods are for --latency-test only)";
  }
  return {};
}

}  // namespace tnv::fwd
