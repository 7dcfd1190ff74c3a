// tnv-fuzz-seed DIR: writes the seed corpus of the five fuzz targets into
// DIR/<target>/ from real protocol frames, request sequences, scenario
// files (the documented keys, every fault kind, typical mistakes) and
// parameter images. Run once and check the result in (tests/fuzz/corpus/).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "firmware/can/param_image.hpp"
#include "firmware/can/param_table.hpp"
#include "tests/firmware/can/bore_frames.hpp"
#include "firmware/can/segment_wire.hpp"
#include "tests/firmware/can/can_test_doubles.hpp"

namespace {

namespace fs = std::filesystem;
namespace can = tnv::fw::can;
using tnv::hal::CanFrame;
using Bytes = std::vector<std::uint8_t>;
using can::CommandCode;
using can::MessageId;
using can::ParamOp;

void write(const fs::path& dir, const std::string& name, const Bytes& bytes) {
  fs::create_directories(dir);
  std::ofstream out(dir / name, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

// can_frames record: flags, id u16 LE, dlc, 8 data bytes. tick_exponent k
// (with tick_first): 2^k ticks before the frame.
void add_frame(Bytes& out, const CanFrame& f, bool tick_first = false, unsigned tick_exponent = 0) {
  out.push_back(static_cast<std::uint8_t>((f.extended ? 1 : 0) | (tick_first ? 2 : 0) | (tick_exponent & 7u) << 2));
  out.push_back(static_cast<std::uint8_t>(f.id));
  out.push_back(static_cast<std::uint8_t>(f.id >> 8));
  out.push_back(f.dlc);
  for (std::uint8_t b : f.data) out.push_back(b);
}

Bytes frames(std::initializer_list<CanFrame> list, bool ticks = false) {
  Bytes out;
  for (const CanFrame& f : list) add_frame(out, f, ticks);
  return out;
}

std::uint16_t id_of(const char* name) { return can::find_param(name)->id; }

// param_set record: op, selector (bit 7: raw id), aux, value u32 LE.
void add_request(Bytes& out, ParamOp op, std::uint16_t id, std::uint32_t raw) {
  out.push_back(static_cast<std::uint8_t>(op));
  out.push_back(static_cast<std::uint8_t>(0x80u | (id >> 8)));
  out.push_back(static_cast<std::uint8_t>(id));
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(raw >> (8 * i)));
}

std::uint32_t wire(const char* name, double value) { return can::to_wire(*can::find_param(name), value); }

void seed_can_frames(const fs::path& dir) {
  using namespace tnv::test;
  const std::uint8_t n = 1;  // the node id of the fuzzed node (tests/firmware/can/node_bench.hpp kNode)
  int k = 0;
  const auto put = [&](const Bytes& b) { write(dir, "seed-" + std::to_string(k++), b); };
  put(frames({param_request(n, ParamOp::get, id_of("x.sliding.gamma"))}));
  put(frames({param_request(n, ParamOp::set, id_of("x.sliding.gamma"), wire("x.sliding.gamma", 0.25))}));
  put(frames({param_request(n, ParamOp::set, id_of("x.sliding.gamma"), 0x7FC00000u)}));  // NaN
  put(frames({param_request(n, ParamOp::stage, id_of("x.sliding.gamma"), wire("x.sliding.gamma", 0.3)),
              param_request(n, ParamOp::commit, 0)}));
  put(frames({param_request(n, ParamOp::stage, 0xFFFF, 1), param_request(n, ParamOp::discard, 0)}));
  for (std::uint8_t code = 0; code < can::kCommandCodeCount; ++code)
    put(frames({command(n, static_cast<CommandCode>(code), 0, 1, 0.5)}));
  put(frames({command(n, CommandCode::enable), circle(n, 6.0, 2.0)}, true));
  put(frames({command(n, CommandCode::enable), jog(n, 0, 1.0), jog(n, 1, -1.0), jog(n, 0, 0.0), jog(n, 1, 0.0)}, true));
  put(frames({command(n, CommandCode::enable), move(n, 0, 2.0, 1.0)}, true));
  put(frames({command(n, CommandCode::enable), circle(n, 6.0, 2.0), frame_to(MessageId::estop, n)}, true));
  put(frames({frame_to(MessageId::estop, can::kBroadcastNode), command(can::kBroadcastNode, CommandCode::stop)}));
  put(frames({command(can::kBroadcastNode, CommandCode::enable)}));
  put(frames({capture_control(n, can::CaptureOp::arm), capture_control(n, can::CaptureOp::status),
              capture_control(n, can::CaptureOp::abort), capture_control(n, can::CaptureOp::upload, 4, 0)},
             true));
  put(frames({command(n, CommandCode::save_params), command(n, CommandCode::load_params),
              command(n, CommandCode::restore_defaults)}));
  // a second host: its own staged set, refused commands, ownership handed over
  put(frames({with_tag(param_request(n, ParamOp::stage, id_of("x.sliding.gamma"), wire("x.sliding.gamma", 0.3)), 0x21),
              param_request(n, ParamOp::stage, id_of("y.sliding.gamma"), wire("y.sliding.gamma", 0.3)),
              with_tag(param_request(n, ParamOp::commit, 0), 0x22), param_request(n, ParamOp::commit, 0),
              with_tag(param_request(n, ParamOp::discard, 0), 0x23)}));
  put(frames({with_tag(command(n, CommandCode::enable), 0x21), with_tag(command(n, CommandCode::take_ownership), 0x22),
              command(n, CommandCode::release_ownership), with_tag(command(n, CommandCode::take_ownership), 0x23),
              with_tag(command(n, CommandCode::enable), 0x24)}));
  put(frames({with_tag(command(n, CommandCode::enable), 0x00), with_tag(param_request(n, ParamOp::get, 1), 0x0F)}));
  CanFrame shaper = frame_to(MessageId::shaper, n);
  put(frames({shaper}));
  // other nodes, extended, wrong lengths, to-host messages sent to the node
  put(frames({param_request(2, ParamOp::set, id_of("x.sliding.gamma"), wire("x.sliding.gamma", 0.25)),
              command(can::kMaxNodeId, CommandCode::enable)}));
  CanFrame ext = param_request(n, ParamOp::get, 1);
  ext.extended = true;
  put(frames({ext}));
  CanFrame shorter = command(n, CommandCode::enable);
  shorter.dlc = 3;
  CanFrame empty = param_request(n, ParamOp::get, 1);
  empty.dlc = 0;
  put(frames({shorter, empty}));
  put(frames({frame_to(MessageId::heartbeat, n), frame_to(MessageId::param_reply, n), frame_to(MessageId::capture_data, n)}));
  CanFrame unknown{can::make_can_id(0x1F, n), false, 8, {}};
  put(frames({unknown}));
  // Programs: elements (a dwell alone, lines and arcs as SEGMENT + SEGMENT_TAIL), program
  // commands, a tail without its head, a head without its tail, another host's element.
  const auto element = [&](const tnv::fw::motion::Segment& s, std::uint8_t tag, Bytes& out, bool ticks) {
    can::SegmentFrames f;
    can::encode_segment(s, {0.0, 0.0}, n, tag, f);
    add_frame(out, f.head, ticks);
    if (f.has_z) add_frame(out, f.z);
    if (f.has_tail) add_frame(out, f.tail);
  };
  Bytes program;
  add_frame(program, command(n, CommandCode::enable));
  element(tnv::fw::motion::line_to({2.0, 0.0}, 5.0), 0x11, program, true);
  element(tnv::fw::motion::dwell_for(0.02), 0x12, program, false);
  element(tnv::fw::motion::arc_to(false, {2.0, 2.0}, {2.0, 1.0}, 5.0), 0x13, program, false);
  add_frame(program, command(n, CommandCode::end_program));
  add_frame(program, command(n, CommandCode::program_status), true, 4);
  put(program);
  program.clear();
  add_frame(program, command(n, CommandCode::enable));
  element(tnv::fw::motion::line_to({5.0, 1.0}, 10.0), 0x11, program, true);
  add_frame(program, command(n, CommandCode::feed_override, 0, 50));
  add_frame(program, command(n, CommandCode::feed_hold), true, 3);
  add_frame(program, command(n, CommandCode::feed_resume), true, 3);
  add_frame(program, command(n, CommandCode::abort_program), true, 2);
  put(program);
  program.clear();
  can::SegmentFrames half;
  can::encode_segment(tnv::fw::motion::line_to({1.0, 1.0}, 2.0), {0.0, 0.0}, n, 0x14, half);
  add_frame(program, command(n, CommandCode::enable));
  add_frame(program, half.tail);                                 // no head
  add_frame(program, half.head);                                 // a head, then another: not_ready
  element(tnv::fw::motion::line_to({0.0, 1.0}, 2.0), 0x15, program, false);
  element(tnv::fw::motion::line_to({3.0, 0.0}, 2.0), 0x21, program, false);  // host 2: not_owner
  element(tnv::fw::motion::line_to({300.0, 0.0}, 2.0), 0x16, program, false);  // outside the workspace
  put(program);
  // Deep states, with tick steps between the frames: a capture recorded and
  // uploaded while foreign frames arrive mid-upload, a commit of a staged
  // set, a circle past its dwell, an excitation run out.
  const std::uint32_t immediate = static_cast<std::uint32_t>(can::CaptureTrigger::immediate);
  Bytes deep;
  add_frame(deep, param_request(n, ParamOp::set, id_of("capture.trigger"), immediate));
  add_frame(deep, capture_control(n, can::CaptureOp::arm));
  add_frame(deep, capture_control(n, can::CaptureOp::status), true, 5);
  add_frame(deep, capture_control(n, can::CaptureOp::abort));
  add_frame(deep, capture_control(n, can::CaptureOp::upload, 255, 0));
  add_frame(deep, param_request(2, ParamOp::get, id_of("x.sliding.gamma")), true);
  add_frame(deep, command(5, CommandCode::enable), true);
  add_frame(deep, capture_control(n, can::CaptureOp::upload, 40, 28), true, 3);
  put(deep);
  deep.clear();
  add_frame(deep, param_request(n, ParamOp::stage, id_of("x.sliding.gamma"), wire("x.sliding.gamma", 0.3)));
  add_frame(deep, param_request(n, ParamOp::stage, id_of("tlm.heartbeat_ms"), 10));
  add_frame(deep, param_request(n, ParamOp::stage, id_of("tlm.position_ms"), 1));
  add_frame(deep, param_request(n, ParamOp::commit, 0));
  add_frame(deep, param_request(n, ParamOp::set, id_of("motion.circle_dwell_s"), wire("motion.circle_dwell_s", 0.05)));
  add_frame(deep, command(n, CommandCode::enable), true);
  add_frame(deep, circle(n, 6.0, 2.0), true);
  add_frame(deep, capture_control(n, can::CaptureOp::status), true, 6);  // past the 50-tick dwell
  add_frame(deep, command(n, CommandCode::stop), true);
  add_frame(deep, command(n, CommandCode::clear_faults), true, 5);
  put(deep);
  deep.clear();
  CanFrame excite = frame_to(MessageId::excite, n);
  set_raw(excite, MessageId::excite, "duration", 100);
  set_value(excite, MessageId::excite, "level", 2.0);
  add_frame(deep, command(n, CommandCode::enable));
  add_frame(deep, excite, true, 2);
  add_frame(deep, capture_control(n, can::CaptureOp::status), true, 5);
  add_frame(deep, command(n, CommandCode::save_params), true);
  add_frame(deep, command(n, CommandCode::load_params));
  put(deep);
  // Boring on the board (the fuzzed node's planner is on): a start-up part, parts
  // learned by RLS, a save and a load between them, a restart; then the refusals.
  using can::BoreOp;
  deep.clear();
  add_frame(deep, bore_gauge(n, BoreOp::query));
  add_frame(deep, bore_gauge(n, BoreOp::record, 1, 0.0485, 0.1689));
  add_frame(deep, bore_gauge(n, BoreOp::record, 2, 0.0102, -0.0213), true);
  add_frame(deep, command(n, CommandCode::save_params));
  add_frame(deep, bore_gauge(n, BoreOp::record, 3, 0.0611, 0.0933), true);
  add_frame(deep, command(n, CommandCode::load_params), true);
  add_frame(deep, bore_gauge(n, BoreOp::record, 3, -0.0402, 0.0033));
  add_frame(deep, with_tag(bore_gauge(n, BoreOp::query), 0x27));
  add_frame(deep, bore_gauge(n, BoreOp::restart));
  put(deep);
  CanFrame no_reading = bore_gauge(n, BoreOp::record, 1, 0.02, 0.02);
  set_raw(no_reading, MessageId::bore_gauge, "bottom", 0x8000u);
  CanFrame bad_op = bore_gauge(n, BoreOp::query);
  set_raw(bad_op, MessageId::bore_gauge, "op", 7);
  CanFrame short_gauge = bore_gauge(n, BoreOp::record, 1, 0.02, 0.02);
  short_gauge.dlc = 7;
  put(frames({no_reading, bore_gauge(n, BoreOp::record, 5, 0.02, 0.02), bad_op, short_gauge,
              with_tag(bore_gauge(n, BoreOp::restart), 0x31), bore_gauge(n, BoreOp::record, 1, -3.0, 0.02),
              param_request(n, ParamOp::set, id_of("bore.enable"), 0), bore_gauge(n, BoreOp::query)}));
  put(frames({param_request(n, ParamOp::stage, id_of("bore.l2_mm"), wire("bore.l2_mm", 40.5)),
              param_request(n, ParamOp::commit, 0),
              param_request(n, ParamOp::set, id_of("bore.gain_form"), 2),
              param_request(n, ParamOp::set, id_of("bore.reset_after"), 1),
              bore_gauge(n, BoreOp::record, 1, 0.0485, 0.1689), bore_gauge(n, BoreOp::record, 2, 0.2, 0.3),
              bore_gauge(n, BoreOp::record, 3, 0.2, 0.3), param_request(n, ParamOp::get, id_of("bore.c_hat_mm"))}));
}

// frame_codec: every message of the table, to and from the node, with
// typical field values, plus foreign and malformed identifiers.
void seed_frame_codec(const fs::path& dir) {
  int k = 0;
  const auto put = [&](const Bytes& b) { write(dir, "seed-" + std::to_string(k++), b); };
  for (const can::MessageDef& m : can::kMessages) {
    Bytes b;
    CanFrame f = can::make_frame(m, 1);
    add_frame(b, f);
    for (std::size_t i = 0; i < f.data.size(); ++i) f.data[i] = static_cast<std::uint8_t>(0x11 * (i + 1));
    add_frame(b, f);
    f.data.fill(0xFF);
    add_frame(b, f);
    put(b);
  }
  CanFrame ext = can::make_frame(can::kMessages[2], 1);
  ext.extended = true;
  CanFrame unknown{can::make_can_id(0x1F, 1), false, 8, {}};
  put(frames({ext, unknown}));
}

void seed_param_set(const fs::path& dir) {
  int k = 0;
  const auto put = [&](const Bytes& b) { write(dir, "seed-" + std::to_string(k++), b); };
  // each read_write parameter: get, then stage its current value and commit (a few per file)
  Bytes batch;
  int in_batch = 0;
  for (const can::ParamDef& p : can::param_table()) {
    add_request(batch, ParamOp::get, p.id, 0);
    if (p.access == can::Access::read_write) {
      add_request(batch, ParamOp::stage, p.id, can::to_wire(p, p.min));
      add_request(batch, ParamOp::stage, p.id, can::to_wire(p, p.max));
    }
    if (++in_batch == 6) {
      add_request(batch, ParamOp::commit, 0, 0);
      put(batch);
      batch.clear();
      in_batch = 0;
    }
  }
  if (!batch.empty()) put(batch);
  Bytes b;
  add_request(b, ParamOp::set, id_of("x.sliding.gamma"), wire("x.sliding.gamma", 0.25));
  add_request(b, ParamOp::set, id_of("x.sliding.gamma"), 0xFF800000u);  // -inf
  add_request(b, ParamOp::stage, id_of("y.sliding.gamma"), wire("y.sliding.gamma", 0.5));
  add_request(b, ParamOp::discard, 0, 0);
  add_request(b, ParamOp::commit, 0, 0);
  put(b);
  b.clear();
  add_request(b, ParamOp::stage, 0x7777, 5);
  add_request(b, ParamOp::set, 0x0000, 5);
  add_request(b, static_cast<ParamOp>(4), 0, 0);
  put(b);
}

void seed_scenarios(const fs::path& dir) {
  const std::vector<std::string> texts = {
      "",
      "name = \"no-cut\"\n",
      "name = \"cut-900\"\n[plant.x]\ntau_s = 0.005360\ngain = 1.0\ncoulomb_mm_s = 1.5\nstiction_mm_s = 3.0\n"
      "stribeck_mm_s = 0.1\nmode_hz = 0.0\nmode_zeta = 0.0\n[cutting]\nenabled = true\nspindle_rpm = 900\nflutes = 2\n"
      "mean_mm_s = 0.6\namplitude_mm_s = 0.6\nexponent = 0.75\nphase_rad = 0.0\n",
      "[encoder]\ncounts_per_rev = 24000\nlead_mm = 10.0\noffset_counts_x = 0.25\noffset_counts_y = -0.5\n",
      "[dac]\nbits = 12\nfull_scale_v = 10.0\nrpm_at_full_scale = 1000.0\n[force_sensor]\nvolts_per_mm_s = 1.0\n"
      "volts_per_n = 0.0333\n",
      "[milling]\nenabled = true\ntime_constant_s = 0.2\nforce_n_per_mm_mm_s = 15.0\nfeed_load_mm_s_per_n = 0.004\n"
      "depth_start_mm = 0.2\ndepth_peak_mm = 1.0\nrise_s = 15.0\nfall_s = 15.0\n",
      "[board]\nclock_start = 4294967000\n[circle]\nradius_mm = 6.0\nfeed_mm_s = 2.0\nramp_s = 0.1\ndwell_s = 0.5\n",
      "[plant.y]\ntau_s = 0.007122\nmode_hz = 30.0\nmode_zeta = 0.02\n",
      "[[fault]]\nkind = \"estop\"\nstart_s = 1.0\nduration_s = 0.5\n",
      "[[fault]]\nkind = \"servo_alarm\"\nstart_s = 0.2\naxis = \"y\"\n",
      "[[fault]]\nkind = \"limit_switch\"\nstart_s = 0.3\naxis = \"x\"\nside = \"-\"\nduration_s = 1\n",
      "[[fault]]\nkind = \"encoder_illegal\"\nstart_s = 0.4\naxis = \"x\"\n",
      "[[fault]]\nkind = \"encoder_dead\"\nstart_s = 0.5\naxis = \"y\"\nduration_s = 0.1\n",
      "[[fault]]\nkind = \"dac_stuck\"\nstart_s = 3.0\nduration_s = 0.5\naxis = \"x\"\ncode = 2648\n",
      "[[fault]]\nkind = \"missed_tick\"\nstart_s = 0.6\nticks = 3\n",
      "[[fault]]\nkind = \"late_tick\"\nstart_s = 0.7\ndelay_us = 1500\n",
      "[[fault]]\nkind = \"stale_snapshot\"\nstart_s = 0.8\nduration_s = 0.01\n",
      "[[fault]]\nkind = \"runaway\"\nstart_s = 0.9\naxis = \"x\"\n",
      "[[fault]]\nkind = \"bus_read_error\"\nstart_s = 1.1\nduration_s = 0.002\n",
      "[[fault]]\nkind = \"estop\"\nstart_s = 0.0\n[[fault]]\nkind = \"estop\"\nstart_s = 0.0\nduration_s = 0.00001\n"
      "[[fault]]\nkind = \"missed_tick\"\nstart_s = 0.0\nticks = 10000\n",
      // mistakes the parser must refuse with one line
      "[plant.x]\ntau_s = -1\n",
      "[plant.x]\ntau_s = nan\n",
      "[dac]\nbits = 12.5\n",
      "[nonsense]\nkey = 1\n",
      "name = 5\n",
      "[[fault]]\nkind = \"dac_stuck\"\nstart_s = 1\naxis = \"x\"\n",
      "[[fault]]\nkind = \"estop\"\nstart_s = 1\nside = \"+\"\n",
      "[[fault]]\nkind = \"teleport\"\nstart_s = 1\n",
      "[circle\nradius_mm = 6\n",
      "[encoder]\ncounts_per_rev = 24001\n",
  };
  for (std::size_t i = 0; i < texts.size(); ++i) write(dir, "seed-" + std::to_string(i), Bytes(texts[i].begin(), texts[i].end()));
}

Bytes image(const can::NodeSettings& s) {
  Bytes out(can::kParamImageMaxBytes);
  out.resize(can::encode_image(s, out));
  return out;
}

// The same set as a version-2 image (before the boring planner's state).
Bytes image_v2(const can::NodeSettings& s) {
  Bytes out = image(s);
  out.erase(out.end() - static_cast<std::ptrdiff_t>(can::kBoreStateImageBytes + can::kParamImageCrcBytes), out.end());
  out[4] = static_cast<std::uint8_t>(can::kParamImageVersion2);
  const std::uint32_t crc = can::crc32(out);
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(crc >> (8 * i)));
  return out;
}

// A set whose boring planner has learned three parts.
can::NodeSettings learned(can::NodeSettings s) {
  s.bore.enabled = true;
  const double readings[3][2] = {{0.0485, 0.1689}, {0.0102, -0.0213}, {0.0611, 0.0933}};
  for (const auto& r : readings) tnv::fw::record_bored_part(s.bore, s.bore_state, {r[0], r[1]}, 2e-5);
  return s;
}

void seed_images(const fs::path& dir) {
  const can::NodeSettings d = can::default_node_settings();
  can::NodeSettings a = d;
  a.firmware.axis[0].sliding.gamma = 0.25;
  can::NodeSettings b = d;
  b.firmware.axis[1].sliding.gamma = 0.125;
  int k = 0;
  const auto put = [&](std::uint8_t flags, const Bytes& current, const Bytes& previous) {
    Bytes out(1 + current.size() + previous.size(), flags);
    std::copy(current.begin(), current.end(), out.begin() + 1);
    std::copy(previous.begin(), previous.end(), out.begin() + 1 + static_cast<std::ptrdiff_t>(current.size()));
    write(dir, "seed-" + std::to_string(k++), out);
  };
  for (std::uint8_t flags = 0; flags < 4; ++flags) {
    const bool two = (flags & 1u) != 0;
    put(flags, image(d), two ? image(d) : Bytes{});
    put(flags, image(a), two ? image(b) : Bytes{});
    Bytes bad = image(a);
    bad[30] ^= 0x40;
    put(flags, bad, two ? image(b) : Bytes{});
    Bytes truncated = image(b);
    truncated.resize(truncated.size() / 2);
    put(flags, truncated, two ? Bytes(truncated.size(), 0) : Bytes{});
    Bytes header_only = image(a);
    header_only.resize(can::kParamImageHeaderBytes);
    put(flags, header_only, two ? header_only : Bytes{});
    Bytes wrong_version = image(a);
    wrong_version[4] = static_cast<std::uint8_t>(can::kParamImageVersion + 1);
    put(flags, wrong_version, two ? image(a) : Bytes{});
    put(flags, image(learned(a)), two ? image_v2(b) : Bytes{});
    Bytes bad_state = image(learned(b));
    bad_state[bad_state.size() - can::kParamImageCrcBytes - 88] ^= 0x08;  // P(1,2): no longer symmetric
    put(flags, bad_state, two ? image(learned(a)) : Bytes{});
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 || argv[1][0] == '-') {  // "--help" is no directory to write into
    std::fprintf(stderr, "usage: tnv-fuzz-seed DIR\n");
    return 2;
  }
  const fs::path root(argv[1]);
  seed_can_frames(root / "can_frames");
  seed_frame_codec(root / "frame_codec");
  seed_param_set(root / "param_set");
  seed_scenarios(root / "scenario_toml");
  seed_images(root / "param_image");
  return 0;
}
