// _tnv: the Python bindings of the host library (tools/can). Bindings only:
// every decision (how a connection is opened, how a set is staged and
// committed, how a capture is armed and downloaded, what a motion waits
// for) is a tnv_can_host function that tnvctl calls too. The package
// tools/python/tnv wraps this module in its Python API.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "firmware/can/param_table.hpp"
#include "hal/axis.hpp"
#include "tools/can/capture_run.hpp"
#include "tools/can/motion_run.hpp"
#include "tools/can/node_identity.hpp"
#include "tools/can/param_set.hpp"
#include "tools/can/param_text.hpp"
#include "tools/can/spindle_command.hpp"
#include "tools/can/telemetry_json.hpp"
#include "tools/can/telemetry_view.hpp"
#include "tools/can_emu/node_connection.hpp"

namespace py = pybind11;

namespace {

namespace can = tnv::fw::can;
namespace host = tnv::can_host;
using host::Micros;

Micros micros(double s) { return Micros{static_cast<long long>(std::ceil(s * 1e6))}; }

// nlohmann::json -> dict / list / str / int / float / bool / None.
py::object to_python(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::object: {
      py::dict d;
      for (const auto& [k, v] : j.items()) d[py::str(k)] = to_python(v);
      return d;
    }
    case nlohmann::json::value_t::array: {
      py::list l;
      for (const auto& v : j) l.append(to_python(v));
      return l;
    }
    case nlohmann::json::value_t::string: return py::str(j.get<std::string>());
    case nlohmann::json::value_t::boolean: return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer: return py::int_(j.get<long long>());
    case nlohmann::json::value_t::number_unsigned: return py::int_(j.get<unsigned long long>());
    case nlohmann::json::value_t::number_float: return py::float_(j.get<double>());
    default: return py::none();
  }
}

const can::ParamDef& param_named(const std::string& name) {
  if (const can::ParamDef* p = host::find_param_by_text(name)) return *p;
  std::string message = "no parameter '";
  message.append(name).append("'");
  if (const std::string close = host::closest_param_name(name); !close.empty())
    message.append(" (did you mean ").append(close).append("?)");
  throw py::key_error(message);
}

// A value as the node takes it: a number, or a name for enum / boolean
// parameters; checked against the table (ValueError) before anything is sent.
double parse_value(const can::ParamDef& p, const py::handle& value) {
  std::string text;
  if (py::isinstance<py::str>(value)) {
    text = value.cast<std::string>();
  } else if (py::isinstance<py::bool_>(value)) {
    text = value.cast<bool>() ? "1" : "0";
  } else {
    const double v = py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
    if (!std::isfinite(v)) {
      std::string message = p.name;
      throw py::value_error(message.append(": ").append(std::isnan(v) ? "NaN" : "an infinite value").append(
          " is not a value (range ").append(host::range_text(p)).append(")"));
    }
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    text = buf;
  }
  std::string error;
  const std::optional<double> parsed = host::parse_param_value(p, text, error);
  if (!parsed) throw py::value_error(error);
  return *parsed;
}

py::dict param_info(const can::ParamDef& p) {
  py::dict d;
  d["id"] = p.id;
  d["name"] = p.name;
  const char* types[] = {"f32", "u32", "i32", "bool", "enum"};
  d["type"] = types[static_cast<int>(p.type) % 5];
  d["unit"] = p.unit;
  d["min"] = p.min;
  d["max"] = p.max;
  d["range"] = host::range_text(p);
  d["values"] = p.values;
  d["access"] = p.access == can::Access::read_only ? "ro" : "rw";
  d["apply"] = can::to_string(p.apply);
  d["safety"] = can::safety_param(p);
  d["description"] = p.doc;
  return d;
}

py::dict ack_dict(const host::CommandAck& ack) {
  py::dict d;
  d["state"] = tnv::fw::to_string(ack.state);
  d["fault"] = tnv::fw::to_string(ack.fault);
  d["owner"] = ack.owner;
  return d;
}

// One open connection. Every call holds `mutex` and, while it waits on the
// bus, not the GIL: other Python threads run, none enters this node's client.
class Connection {
  // (first: their deduced return types are used below)
  host::NodeConnection& conn() {
    if (!connection_) throw std::runtime_error("the node is closed");
    return *connection_;
  }
  template <typename F>
  auto blocking(F&& f) {
    host::NodeClient& c = conn().client();
    py::gil_scoped_release release;
    std::lock_guard lock(mutex_);
    return f(c);
  }
  template <typename F>
  py::object motion(F&& f) {
    const std::optional<host::Heartbeat> hb = blocking(f);
    if (!hb) return py::none();
    return to_python(host::heartbeat_json(*hb));
  }
  std::vector<host::ParamAssignment> parsed(const std::vector<std::pair<std::string, py::object>>& assignments) {
    std::vector<host::ParamAssignment> changes;
    for (const auto& [name, value] : assignments) {
      const can::ParamDef& p = param_named(name);
      changes.push_back({&p, parse_value(p, value)});
    }
    return changes;
  }

 public:
  explicit Connection(const host::ConnectionOptions& options) {
    std::vector<std::string> notes;
    {
      py::gil_scoped_release release;
      connection_ = host::NodeConnection::open(options, notes);
    }
    notes_ = notes;
  }

  const std::vector<std::string>& notes() const { return notes_; }
  bool emulated() { return conn().emulated() != nullptr; }
  std::string describe() { return conn().client().bus().describe(); }

  double get(const std::string& name) {
    const can::ParamDef& p = param_named(name);
    return blocking([&](host::NodeClient& c) { return c.get(p); });
  }

  // Values read back after the commit, one per assignment.
  std::vector<double> set(const std::vector<std::pair<std::string, py::object>>& assignments) {
    const std::vector<host::ParamAssignment> changes = parsed(assignments);
    return blocking([&](host::NodeClient& c) {
      const std::vector<double> staged = host::stage_params(c, changes);
      return host::commit_params(c, changes, staged);
    });
  }
  double stage(const std::string& name, const py::object& value) {
    const can::ParamDef& p = param_named(name);
    const std::vector<host::ParamAssignment> one{{&p, parse_value(p, value)}};
    const double staged = blocking([&](host::NodeClient& c) { return host::stage_params(c, one).front(); });
    staged_.push_back(one.front());
    staged_values_.push_back(staged);
    return staged;
  }
  std::vector<double> commit() {
    const std::vector<host::ParamAssignment> changes = std::move(staged_);
    const std::vector<double> staged = std::move(staged_values_);
    staged_.clear();
    staged_values_.clear();
    return blocking([&](host::NodeClient& c) { return host::commit_params(c, changes, staged); });
  }
  void discard() {
    staged_.clear();
    staged_values_.clear();
    blocking([](host::NodeClient& c) {
      c.discard();
      return 0;
    });
  }
  std::vector<std::string> staged_names() const {
    std::vector<std::string> names;
    for (const host::ParamAssignment& a : staged_) names.emplace_back(a.param->name);
    return names;
  }

  py::dict command(const std::string& name, int axis, int arg, double value) {
    std::optional<can::CommandCode> code;
    for (int i = 0; i < can::kCommandCodeCount; ++i)
      if (name == can::to_string(static_cast<can::CommandCode>(i))) code = static_cast<can::CommandCode>(i);
    if (!code) throw py::value_error("no command '" + name + "'");
    return ack_dict(blocking([&](host::NodeClient& c) {
      return c.command(*code, static_cast<std::uint8_t>(axis), static_cast<std::uint8_t>(arg), value);
    }));
  }
  py::object move(int axis, double distance_mm, double speed_mm_s, bool wait) {
    return motion([&](host::NodeClient& c) {
      c.move(static_cast<std::uint8_t>(axis), distance_mm, speed_mm_s);
      return wait ? std::optional(host::wait_motion_done(c, "move", host::move_expected_s(c, distance_mm, speed_mm_s)))
                  : std::nullopt;
    });
  }
  py::object circle(std::optional<double> radius_mm, std::optional<double> feed_mm_s, bool wait) {
    return motion([&](host::NodeClient& c) {
      double radius = 6.0;  // S1's circle when the node's scenario is unknown (as tnvctl circle)
      double feed = 2.0;
      if (const host::EmulatedBus* emu = conn().emulated()) {
        radius = emu->scenario().circle.radius_mm;
        feed = emu->scenario().circle.feed_mm_s;
      }
      radius = radius_mm.value_or(radius);
      feed = feed_mm_s.value_or(feed);
      c.circle(radius, feed);
      return wait ? std::optional(host::wait_motion_done(c, "circle", host::circle_expected_s(c, radius, feed)))
                  : std::nullopt;
    });
  }
  py::object home(int axis) {
    return motion([&](host::NodeClient& c) {
      const double bound_s = host::homing_bound_s(c, static_cast<std::uint8_t>(axis));
      c.command(can::CommandCode::home, static_cast<std::uint8_t>(axis));
      const host::Heartbeat hb = host::wait_motion_done(c, "home", bound_s);
      if (const auto why = host::not_homed_message(hb, static_cast<std::uint8_t>(axis))) throw host::MotionFailed(*why);
      return std::optional(hb);
    });
  }
  py::object stop(bool wait) {
    return motion([&](host::NodeClient& c) {
      c.command(can::CommandCode::stop);
      return wait ? std::optional(host::wait_motion_done(c, "stop", 10.0)) : std::nullopt;
    });
  }
  // The spindle as `tnvctl spindle`: checked, sent, answered (docs/safety.md "Spindle").
  py::dict spindle_start(const std::string& direction, double rpm) {
    const tnv::fw::SpindleDirection d = host::spindle_direction_named(direction);  // ValueError before sending
    return ack_dict(blocking(
        [&](host::NodeClient& c) { return host::spindle_command(c, can::SpindleOp::start, d, rpm); }));
  }
  py::dict spindle_stop() {
    return ack_dict(blocking([](host::NodeClient& c) { return host::spindle_command(c, can::SpindleOp::stop); }));
  }
  py::dict clear_faults() {
    bool retried = false;
    py::dict d = ack_dict(blocking([&](host::NodeClient& c) { return host::clear_faults(c, retried); }));
    d["retried"] = retried;
    return d;
  }
  py::dict status() {
    struct Status {
      host::Heartbeat hb;
      host::CaptureStatus capture;
      host::NodeIdentity id;
      host::ProgramTool tool;
    };
    const Status s = blocking([](host::NodeClient& c) {
      Status out;
      out.hb = c.wait_heartbeat(std::max(c.options().timeout, Micros{1'000'000}));
      out.capture = c.capture(can::CaptureOp::status);
      out.id = host::read_identity(c);
      out.tool = c.program_tool();
      return out;
    });
    py::dict d(to_python(host::heartbeat_json(s.hb)));
    d["capture"] = host::capture_state_name(s.capture.state);
    d["capture_samples"] = s.capture.samples;
    d["firmware"] = host::firmware_version_text(s.id.firmware_version);
    d["build_id"] = host::build_id_text(s.id.build_id);
    d["protocol_version"] = s.id.protocol_version;
    // The tool the node knows in the spindle (PROGRAM_TOOL); None when it does not know (never guessed).
    d["tool_in_spindle"] = s.tool.known ? py::object(py::int_(s.tool.tool)) : py::object(py::none());
    return d;
  }

  py::dict arm_capture(const std::string& channels, const std::string& trigger, int decimation) {
    const host::CaptureSetup setup{channels, trigger, decimation};
    host::check_capture_setup(setup);  // std::invalid_argument -> ValueError, before anything is sent
    const host::ArmedCapture armed = blocking([&](host::NodeClient& c) { return host::arm_capture(c, setup); });
    py::dict d;
    d["channels"] = host::channel_list_text(armed.channel_mask);
    d["trigger"] = armed.trigger;
    d["decimation"] = armed.decimation;
    d["state"] = host::capture_state_name(armed.status.state);
    return d;
  }
  void stop_capture_after(double tail_s) {
    blocking([&](host::NodeClient& c) {
      host::stop_capture_after(c, micros(tail_s));
      return 0;
    });
  }
  // {"columns": {name_with_unit: ndarray}, "samples", "decimation", "period_s", "bytes", "upload_s", "rerequests"}
  py::dict download_capture(double wait_s) {
    const host::DownloadedCapture d =
        blocking([&](host::NodeClient& c) { return host::download_capture(c, micros(wait_s)); });
    py::dict columns;
    for (std::size_t i = 0; i < d.table.channels.size(); ++i) {
      const std::vector<double>& col = d.table.columns[i];
      py::array_t<double> a(static_cast<py::ssize_t>(col.size()));
      std::copy(col.begin(), col.end(), a.mutable_data());
      columns[py::str(host::column_name(*d.table.channels[i]))] = std::move(a);
    }
    py::dict out;
    out["columns"] = columns;
    out["samples"] = d.status.samples;
    out["decimation"] = d.table.decimation;
    out["period_s"] = d.table.period_s();
    out["bytes"] = d.bytes;
    out["upload_s"] = d.upload_s;
    out["rerequests"] = d.rerequests;
    return out;
  }

  // Telemetry: the listener keeps the latest of everything the node streams;
  // each sample receives for `period_s` (bus clock) and returns what is known.
  void telemetry_start(bool realtime) {
    blocking([&](host::NodeClient& c) {
      view_ = host::TelemetryView{};
      c.set_listener([this](const tnv::hal::CanFrame& f, can::MessageId id) { view_.take(f, id); });
      if (host::EmulatedBus* emu = conn().emulated()) emu->set_realtime(realtime);
      telemetry_start_ = c.bus().now();
      bitrate_bit_s_ = c.get(*can::find_param("can.bitrate_kbit")) * 1000.0;
      return 0;
    });
  }
  py::object telemetry_sample(double period_s) {
    const nlohmann::json j = blocking([&](host::NodeClient& c) {
      c.pump(micros(period_s));
      const double t_s = static_cast<double>((c.bus().now() - telemetry_start_).count()) * 1e-6;
      const double load = t_s > 0.0 ? static_cast<double>(view_.bits) / (t_s * bitrate_bit_s_) : 0.0;
      return host::telemetry_json(view_, t_s, load);
    });
    return to_python(j);
  }
  void telemetry_stop() {
    if (!connection_) return;
    blocking([&](host::NodeClient& c) {
      c.set_listener({});
      if (host::EmulatedBus* emu = conn().emulated()) emu->set_realtime(false);
      return 0;
    });
  }

  // Gives back command ownership and closes the bus; "" or why the release failed.
  std::string close() {
    if (!connection_) return "";
    py::gil_scoped_release release;
    std::lock_guard lock(mutex_);
    std::string error = connection_->release_ownership();
    connection_.reset();
    return error;
  }
  bool closed() const { return !connection_; }

 private:
  std::unique_ptr<host::NodeConnection> connection_;
  std::vector<std::string> notes_;
  std::mutex mutex_;
  std::vector<host::ParamAssignment> staged_;  // this host's stages since the last commit / discard
  std::vector<double> staged_values_;
  host::TelemetryView view_;
  Micros telemetry_start_{0};
  double bitrate_bit_s_ = 1e6;
};

}  // namespace

PYBIND11_MODULE(_tnv, m) {
  m.doc() = "TNV-40 host library bindings (use the tnv package)";
  m.attr("protocol_version") = can::kProtocolVersion;
  // The machine's axes in index order (hal/axis.hpp's list): the axis
  // arguments' values and the order of per-axis lists.
  std::vector<std::string> axes;
  for (const char* name : tnv::hal::kAxisNames) axes.emplace_back(name);
  m.attr("axes") = axes;

  static py::exception<std::runtime_error> exc_error(m, "Error", PyExc_RuntimeError);
  static py::exception<std::runtime_error> exc_refused(m, "Refused", exc_error.ptr());
  static py::exception<std::runtime_error> exc_timeout(m, "Timeout", exc_error.ptr());
  static py::exception<std::runtime_error> exc_bus(m, "BusError", exc_error.ptr());
  static py::exception<std::runtime_error> exc_motion(m, "MotionFailed", exc_error.ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::builtin_exception&) {
      throw;  // KeyError, ValueError, ...: pybind11's own translator
    } catch (const host::RequestError& e) {
      if (e.kind() == host::RequestError::Kind::refused) {
        py::object exc = py::reinterpret_borrow<py::object>(exc_refused.ptr())(e.what());
        exc.attr("code") = can::to_string(e.code());
        PyErr_SetObject(exc_refused.ptr(), exc.ptr());
      } else if (e.kind() == host::RequestError::Kind::timeout) {
        exc_timeout(e.what());
      } else {
        exc_error(e.what());
      }
    } catch (const host::BusError& e) {
      exc_bus(e.what());
    } catch (const host::MotionFailed& e) {
      exc_motion(e.what());
    } catch (const host::ConnectionInputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const std::runtime_error& e) {  // ParamSetMismatch, CaptureError, a node of another protocol
      exc_error(e.what());
    }
  });

  m.def("param_names", [] {
    std::vector<std::string> names;
    for (const can::ParamDef& p : can::param_table()) names.emplace_back(p.name);
    return names;
  });
  m.def("param_info", [](const std::string& name) { return param_info(param_named(name)); },
        "id, name, unit, min, max, range, values, access, apply, safety, description; KeyError for an unknown name");
  m.def("parse_value", [](const std::string& name, const py::object& value) {
    return parse_value(param_named(name), value);
  }, "the value as the node takes it; ValueError when the table refuses it");
  m.def("format_value", [](const std::string& name, double value) {
    return host::format_param_value(param_named(name), value);
  });
  m.def("channel_names", [] {
    std::string error;
    std::vector<std::string> names;
    const std::optional<can::ChannelMask> all = host::parse_channel_list("all", error);
    const std::string text = host::channel_list_text(all.value_or(0));
    std::size_t start = 0;
    while (start <= text.size()) {
      const std::size_t comma = text.find(',', start);
      names.push_back(text.substr(start, comma - start));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    return names;
  });

  py::class_<Connection>(m, "Connection")
      .def(py::init([](const std::string& iface, bool emu, int node, int host_id, int timeout_ms,
                       const std::string& scenario, int seed, const std::string& storage, const std::string& trace) {
             host::ConnectionOptions o;
             o.iface = iface;
             o.emu = emu;
             o.node = node;
             o.host_id = host_id;
             o.timeout_ms = timeout_ms;
             o.emu_scenario = scenario;
             o.emu_seed = seed;
             o.emu_storage = storage;
             o.trace = trace;
             return std::make_unique<Connection>(o);
           }),
           py::arg("iface") = "", py::arg("emu") = false, py::arg("node") = 1, py::arg("host_id") = 1,
           py::arg("timeout_ms") = 250, py::arg("scenario") = "no-cut", py::arg("seed") = 0, py::arg("storage") = "",
           py::arg("trace") = "")
      .def_property_readonly("notes", &Connection::notes)
      .def_property_readonly("emulated", &Connection::emulated)
      .def_property_readonly("closed", &Connection::closed)
      .def("describe", &Connection::describe)
      .def("get", &Connection::get)
      .def("set", &Connection::set)
      .def("stage", &Connection::stage)
      .def("commit", &Connection::commit)
      .def("discard", &Connection::discard)
      .def("staged_names", &Connection::staged_names)
      .def("command", &Connection::command, py::arg("name"), py::arg("axis") = 0, py::arg("arg") = 0,
           py::arg("value") = 0.0)
      .def("move", &Connection::move)
      .def("circle", &Connection::circle)
      .def("home", &Connection::home)
      .def("stop", &Connection::stop)
      .def("spindle_start", &Connection::spindle_start)
      .def("spindle_stop", &Connection::spindle_stop)
      .def("clear_faults", &Connection::clear_faults)
      .def("status", &Connection::status)
      .def("arm_capture", &Connection::arm_capture)
      .def("stop_capture_after", &Connection::stop_capture_after)
      .def("download_capture", &Connection::download_capture)
      .def("telemetry_start", &Connection::telemetry_start)
      .def("telemetry_sample", &Connection::telemetry_sample)
      .def("telemetry_stop", &Connection::telemetry_stop)
      .def("close", &Connection::close);
}
