// tnvctl decode | replay: CAN sessions recorded with --trace (or by
// `candump -l`), read by name and unit, or sent again.
#include <sys/stat.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

#include "firmware/can/frame_codec.hpp"
#include "tools/can/candump_log.hpp"
#include "tools/can/frame_text.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

namespace can = fw::can;
using can_host::Micros;

// A replay keeps the recorded gaps up to this; a longer pause (a person
// thinking at a prompt) is shortened to it.
constexpr double kMaxReplayGapS = 1.0;

struct TraceOptions {
  std::string path;  // "-" = stdin (decode only)
};

// Every record of a trace, or BadInput naming the file and line of the
// first that is not a frame. A FIFO, device or directory is refused (a
// trace is a file; stdin is given as "-").
std::vector<can_host::CandumpRecord> read_trace(const std::string& path) {
  std::ifstream file;
  std::istream* in = &std::cin;
  if (path != "-") {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) throw BadInput(path + ": no such file");
    if (!S_ISREG(st.st_mode)) throw BadInput(path + ": not a regular file");
    file.open(path);
    if (!file) throw BadInput(path + ": cannot be read");
    in = &file;
  }
  std::vector<can_host::CandumpRecord> records;
  std::string line, error;
  for (std::size_t number = 1; std::getline(*in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    std::optional<can_host::CandumpRecord> r = can_host::parse_candump_line(line, error);
    if (!r) throw BadInput((path == "-" ? std::string("stdin") : path) + ":" + std::to_string(number) + ": " + error);
    records.push_back(std::move(*r));
  }
  return records;
}

int run_decode(const TraceOptions& o, Report& report) {
  const std::vector<can_host::CandumpRecord> records = read_trace(o.path);
  report.summary_to_stderr();  // stdout: the frames alone (text, or JSON Lines with --json)
  for (const can_host::CandumpRecord& r : records) {
    const std::string text = can_host::frame_text(r.frame);
    if (report.json_mode()) {
      const nlohmann::json j = {{"t_s", r.t_s}, {"iface", r.iface}, {"id", r.frame.id}, {"text", text}};
      std::cout << j.dump() << '\n';
    } else {
      char stamp[48];
      std::snprintf(stamp, sizeof stamp, "(%.6f) ", r.t_s);
      std::cout << stamp << r.iface << "  " << text << '\n';
    }
  }
  report.data["frames"] = records.size();
  return kExitOk;
}

int run_replay(const TraceOptions& o, Session& session, Report& report) {
  const std::vector<can_host::CandumpRecord> records = read_trace(o.path);  // all checked before anything is sent
  can_host::NodeClient& client = session.client();
  std::uint64_t received = 0;
  client.set_listener([&](const hal::CanFrame& f, can::MessageId id) {
    ++received;
    // The answers, not the cyclic heartbeat and telemetry around them.
    const can::MessageDef* m = can::classify(f);
    const bool cyclic = id == can::MessageId::heartbeat || (m != nullptr && std::string_view(m->name).starts_with("tlm_"));
    if (!cyclic) report.line("  <- " + can_host::frame_text(f));
  });
  std::uint64_t sent = 0;
  std::optional<double> previous_t_s;
  try {
    for (const can_host::CandumpRecord& r : records) {
      const can::MessageDef* m = can::classify(r.frame);
      if (m == nullptr || m->direction != can::Direction::to_node) continue;  // the node's own frames are not resent
      if (previous_t_s) {
        const double gap_s = std::min(std::max(r.t_s - *previous_t_s, 0.0), kMaxReplayGapS);
        client.pump(Micros{static_cast<long long>(gap_s * 1e6)});
      }
      previous_t_s = r.t_s;
      client.send_raw(r.frame);
      ++sent;
      report.line("-> " + can_host::frame_text(r.frame));
    }
    client.pump(Micros{100'000});  // the answers to the last frames
  } catch (...) {
    client.set_listener({});
    throw;
  }
  client.set_listener({});
  report.line("replayed " + std::to_string(sent) + " frames to the node from " + o.path + "; " +
              std::to_string(received) + " frames came back");
  report.data["sent"] = sent;
  report.data["received"] = received;
  return kExitOk;
}

}  // namespace

void add_trace_commands(CLI::App& app, ActionSlot& slot) {
  auto decode = std::make_shared<TraceOptions>();
  CLI::App* decode_cmd = app.add_subcommand(
      "decode", "print a CAN trace (tnvctl --trace, candump -l) by message, field name and unit; - reads stdin");
  decode_cmd->add_option("file", decode->path, "FILE or -")->required();
  decode_cmd->callback([&slot, decode] {
    slot = Action{"decode", false, [decode](Session&, Report& r) { return run_decode(*decode, r); },
                  [decode] {
                    if (decode->path != "-") read_trace(decode->path);
                  }};
  });

  auto replay = std::make_shared<TraceOptions>();
  CLI::App* replay_cmd = app.add_subcommand(
      "replay", "send a trace's host-to-node frames again, with their recorded gaps (at most 1 s), and show the answers");
  replay_cmd->add_option("file", replay->path, "FILE (tnvctl --trace, candump -l)")->required();
  replay_cmd->callback([&slot, replay] {
    slot = Action{"replay", true, [replay](Session& s, Report& r) { return run_replay(*replay, s, r); },
                  [replay] { read_trace(replay->path); }};
  });
}

}  // namespace tnv::tnvctl
