#include "tools/gcode/canon_state.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "tools/gcode/ngc_error.hpp"
#include "tools/gcode/ngc_parameters.hpp"

namespace tnv::gcode {

namespace {

constexpr double kMmPerInch = 25.4;

bool has_code(const std::vector<NgcCode>& codes, int code) {
  return std::any_of(codes.begin(), codes.end(), [code](const NgcCode& c) { return c.code == code; });
}

std::string g_text(int code) {
  return code % 10 == 0 ? "G" + std::to_string(code / 10) : "G" + std::to_string(code / 10) + "." + std::to_string(code % 10);
}

// Modal group of a supported G-code (x 10), or -1.
int g_group(int code) {
  switch (code) {
    case 0: case 10: case 20: case 30: case 51: case 331: case 382: case 383: case 384: case 385:
    case 800: case 730: case 810: case 820: case 830: case 840: case 850: case 860: case 870: case 880: case 890:
      return 1;
    case 40: case 100: case 280: case 281: case 300: case 301: case 530: case 920: case 921: case 922: case 923:
      return 0;
    case 170: case 180: case 190: return 2;
    case 900: case 910: return 3;
    case 901: case 911: return 4;
    case 930: case 940: return 5;
    case 200: case 210: return 6;
    case 400: case 410: case 420: case 411: case 421: return 7;
    case 430: case 431: case 490: return 8;
    case 980: case 990: return 10;
    case 540: case 550: case 560: case 570: case 580: case 590: case 591: case 592: case 593: return 12;
    case 610: case 611: case 640: return 13;
    default: return -1;
  }
}

std::string unsupported_g(int code) {
  return "unsupported G-code " + g_text(code);
}

int m_group(int code) {
  switch (code) {
    case 0: case 1: case 2: case 30: case 60: return 4;
    case 6: return 6;
    case 3: case 4: case 5: return 7;
    case 7: case 8: case 9: return 8;
    default: return -1;
  }
}

}  // namespace

std::string fixed(double v, int decimals) {
  char buf[64];
  if (std::fabs(v) < 0.5 * std::pow(10.0, -decimals)) v = 0.0;  // no "-0.0000"
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}


CanonMachine::CanonMachine(const CanonSetup& setup, const CanonSink& sink)
    : setup_(setup), sink_(sink), params_(setup.parameters), tools_(setup.tools) {
  params_.set_machine(this);
}

namespace {

// The calls LinuxCNC lets wait behind a compensated move still in its queue
// (interp_queue.cc); every other call is made at once.
bool waits_behind_queued_moves(const std::string& text) {
  static constexpr const char* kWaiting[] = {"SET_FEED_RATE(", "DWELL(", "SET_FEED_MODE(", "MIST_ON(", "MIST_OFF(",
                                             "FLOOD_ON(", "FLOOD_OFF(", "START_SPINDLE_", "STOP_SPINDLE_TURNING(",
                                             "SET_SPINDLE_MODE(", "SET_SPINDLE_SPEED(", "COMMENT("};
  for (const char* prefix : kWaiting)
    if (text.rfind(prefix, 0) == 0) return true;
  return false;
}

}  // namespace

void CanonMachine::emit(const std::string& text, const CanonMotion& motion) {
  if (text.rfind("STRAIGHT_", 0) == 0 || text.rfind("ARC_FEED(", 0) == 0 || text.rfind("NURBS_FEED(", 0) == 0 ||
      text.rfind("RIGID_TAP(", 0) == 0)
    tool_after_g40_machine_.reset();  // the tool moved on
  if (muted_) return;
  if (!queue_.empty() && waits_behind_queued_moves(text)) {
    Queued q;
    q.line = line_;
    q.file = file_;
    q.text = text;
    q.motion = motion;
    queue_.push_back(std::move(q));
    return;
  }
  sink_(CanonCall{line_, text, motion, file_});
}

CanonMotion CanonMachine::move_to(CanonMotion::Kind kind, const Vec3& program_mm) const {
  CanonMotion m;
  m.kind = kind;
  m.end_mm = program_to_machine(program_mm);
  return m;
}

std::string CanonMachine::num(double mm) const { return fixed(mm / unit_mm_, 4); }

std::string CanonMachine::xyz(const Vec3& p) const {
  return num(p[0]) + ", " + num(p[1]) + ", " + num(p[2]) + ", 0.0000, 0.0000, 0.0000";
}

void CanonMachine::emit_g5x() { emit("SET_G5X_OFFSET(" + std::to_string(origin_) + ", " + xyz(g5x_) + ")"); }
void CanonMachine::emit_g92() { emit("SET_G92_OFFSET(" + xyz(g92_) + ")"); }

void CanonMachine::start() {
  const double selected = params_.get(ngc_number::kG5xSelected, 1);
  origin_ = (selected >= 1.0 && selected <= 9.0) ? static_cast<int>(selected) : 1;
  for (int a = 0; a < 3; ++a) {
    g5x_[static_cast<std::size_t>(a)] = params_.get(ngc_number::kG5xBase + 20 * (origin_ - 1) + a, 1);
    g92_[static_cast<std::size_t>(a)] = params_.get(ngc_number::kG92Enabled, 1) != 0.0 ? params_.get(ngc_number::kG92Base + a, 1) : 0.0;
  }
  params_.set(ngc_number::kG5xSelected, origin_, 1);
  pos_ = canon_pos_ = machine_to_program(setup_.start_machine_mm);
  emit("USE_LENGTH_UNITS(CANON_UNITS_MM)");
  emit_g5x();
  emit_g92();
  emit("SET_XY_ROTATION(0.0000)");
  emit("SET_FEED_REFERENCE(CANON_XYZ)");
  emit("ON_RESET()");
}

CanonMachine::Vec3 CanonMachine::machine_to_program(const Vec3& m) const {
  Vec3 p{};
  for (std::size_t a = 0; a < 3; ++a) p[a] = m[a] - g5x_[a] - g92_[a] - tool_offset_[a];
  return p;
}

CanonMachine::Vec3 CanonMachine::program_to_machine(const Vec3& p) const {
  Vec3 m{};
  for (std::size_t a = 0; a < 3; ++a) m[a] = p[a] + g5x_[a] + g92_[a] + tool_offset_[a];
  return m;
}

void CanonMachine::comments(const NgcBlock& block, int line) {
  line_ = line;
  started_ = true;
  run_comments(block);
}

// "(debug, text #1 #<name>)": the text with each parameter's value (%f);
// a named one not defined shows as ######, as LinuxCNC prints it.
std::string CanonMachine::substitute(const std::string& text) const {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '#') {
      out.push_back(text[i]);
      continue;
    }
    char buf[64];
    if (i + 1 < text.size() && text[i + 1] == '<') {
      const std::size_t close = text.find('>', i);
      if (close == std::string::npos) {
        out.append(text.substr(i));
        break;
      }
      std::string name;
      for (std::size_t k = i + 2; k < close; ++k)
        if (text[k] != ' ' && text[k] != '\t') name.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(text[k]))));
      if (params_.exists(name)) {
        std::snprintf(buf, sizeof buf, "%f", params_.get(name, 1));
        out.append(buf);
      } else {
        out.append("######");
      }
      i = close;
      continue;
    }
    std::size_t end = i + 1;
    while (end < text.size() && std::isdigit(static_cast<unsigned char>(text[end]))) ++end;
    if (end == i + 1 || end - i > 6) {
      out.push_back('#');
      continue;
    }
    const int number = std::stoi(text.substr(i + 1, end - i - 1));
    if (number >= NgcParameters::kCount) {
      out.append(text.substr(i, end - i));
    } else {
      std::snprintf(buf, sizeof buf, "%f", params_.get(number, 1));
      out.append(buf);
    }
    i = end - 1;
  }
  return out;
}

void CanonMachine::run_comments(const NgcBlock& block) {
  for (const std::string& c : block.comments) {
    std::string lower = c;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char ch) { return std::tolower(ch); });
    const std::string head = lower.substr(0, 6);
    if (head.rfind("msg,", 0) == 0) emit("MESSAGE(\"" + c.substr(4) + "\")");
    else if (head == "debug,") emit("MESSAGE(\"" + substitute(c.substr(6)) + "\")");
    else if (head == "print,") continue;  // rs274 prints it on its own output, not as a call
    // LOG* are calls rs274 prints; no file is opened or written here.
    else if (lower.rfind("logopen,", 0) == 0) emit("LOGOPEN(\"" + (log_file_ = c.substr(8)) + "\")");
    else if (lower.rfind("logappend,", 0) == 0) emit("LOGAPPEND(\"" + (log_file_ = c.substr(10)) + "\")");
    else if (lower == "logclose") { log_file_.clear(); emit("LOGCLOSE()"); }
    else if (lower.rfind("log,", 0) == 0) emit("LOG(\"" + substitute(c.substr(4)) + "\")");
    else emit("COMMENT(\"" + c.substr(std::min(c.find_first_not_of(" \t"), c.size())) + "\")");
  }
}

void CanonMachine::apply_assignments(const NgcBlock& block) {
  for (const NgcAssignment& a : block.assignments) {
    if (a.name.empty()) params_.set(a.number, a.value, a.column);
    else params_.assign(a.name, a.value, a.column);
  }
}

void CanonMachine::percent(int line, int column) {
  line_ = line;
  if (!started_ && !percent_started_) {
    percent_started_ = true;
  } else if (percent_started_) {
    comp_flush_here();
    emit("FINISH()", kind_only(CanonMotion::Kind::end));
    ended_ = true;
  } else {
    throw NgcError(column, "'%' after the program started (only as its first and last line)");
  }
}

void CanonMachine::end_of_file(int line) {
  line_ = line;
  throw NgcError(1, "file ended with no percent sign or program end (M2, M30)");
}

void CanonMachine::end_at_end_of_file(int line) {
  line_ = line;
  comp_flush_here();
}

std::array<double, 2> CanonMachine::polar_xy(const NgcBlock& block, double x0, double y0) const {
  const double r0 = std::hypot(x0, y0);
  const double a0 = std::atan2(y0, x0) * 180.0 / std::numbers::pi;
  const double r = absolute_ ? (block.polar_radius ? length(*block.polar_radius) : r0)
                             : r0 + length(block.polar_radius.value_or(0.0));
  const double a = absolute_ ? block.polar_angle.value_or(a0) : a0 + block.polar_angle.value_or(0.0);
  return {r * std::cos(a * std::numbers::pi / 180.0), r * std::sin(a * std::numbers::pi / 180.0)};
}

CanonMachine::Vec3 CanonMachine::target(const NgcBlock& block, bool machine) const {
  const Vec3& from = base_point();
  Vec3 t = from;
  if (block.polar_radius || block.polar_angle) {  // LinuxCNC's @ (radius) and ^ (angle, degrees) in XY
    const int column = block.polar_radius ? block.polar_radius_column : block.polar_angle_column;
    if (block.has('x') || block.has('y')) throw NgcError(column, "polar @/^ with X or Y on one line");
    if (plane_ != 170) throw NgcError(column, "polar @/^ only in the XY plane (G17)");
    if (machine) throw NgcError(column, "polar @/^ with G53");
    const std::array<double, 2> xy = polar_xy(block, from[0], from[1]);
    t[0] = xy[0];
    t[1] = xy[1];
    if (block.has('z')) t[2] = absolute_ ? length(block.value('z')) : from[2] + length(block.value('z'));
    return t;
  }
  static constexpr char kAxes[3] = {'x', 'y', 'z'};
  for (std::size_t a = 0; a < 3; ++a) {
    if (!block.has(kAxes[a])) continue;
    const double v = length(block.value(kAxes[a]));
    if (machine) t[a] = v - g5x_[a] - g92_[a] - tool_offset_[a];
    else t[a] = absolute_ ? v : from[a] + v;
  }
  return t;
}

void CanonMachine::move_traverse(const Vec3& to) {
  emit("STRAIGHT_TRAVERSE(" + xyz(to) + ")", move_to(CanonMotion::Kind::traverse, to));
  pos_ = canon_pos_ = to;
}

void CanonMachine::move_feed(const Vec3& to, int column) {
  if (feed_ <= 0.0) throw NgcError(column, "cannot do G1 with zero feed rate (F)");
  emit("STRAIGHT_FEED(" + xyz(to) + ")", move_to(CanonMotion::Kind::feed, to));
  pos_ = canon_pos_ = to;
}

void CanonMachine::inverse_time_rate(const NgcBlock& block, double length_mm) {
  const double rate = std::max(0.1, length_mm / unit_mm_ * block.value('f'));  // program units per minute
  feed_ = rate;
  emit("SET_FEED_RATE(" + fixed(rate, 4) + ")", valued(CanonMotion::Kind::feed_rate, rate * unit_mm_));
}

void CanonMachine::arc(const NgcBlock& block, bool clockwise, const Vec3& end, int column) {
  if (arc_not_allowed_)
    throw NgcError(column, "the move just after turning cutter radius compensation off (G40) must be straight, not an arc");
  if (inverse_time_ && !block.has('f'))
    throw NgcError(column, "inverse-time feed (G93): an arc needs its own F on its line");
  if (!inverse_time_ && feed_ <= 0.0) throw NgcError(column, "cannot make an arc with zero feed rate (F)");
  // (first, second, axis) as LinuxCNC orders them per plane.
  std::size_t i1 = 0, i2 = 1, ia = 2;
  if (plane_ == 180) { i1 = 2; i2 = 0; ia = 1; }
  if (plane_ == 190) { i1 = 1; i2 = 2; ia = 0; }
  const char other = plane_ == 170 ? 'k' : plane_ == 180 ? 'j' : 'i';
  if (block.has(other)) throw NgcError(block.column(other), std::string("word ") + static_cast<char>(std::toupper(other)) + " is not in the arc's plane");
  if (comp_active()) {  // only ever on in G17 or G18, the plane it was turned on in
    if (inverse_time_) throw NgcError(column, "an arc in inverse-time feed (G93) with cutter radius compensation is not supported");
    comp_arc(block, clockwise, end, column);
    return;
  }
  const ArcFit fit = arc_fit(block, clockwise, pos_[i1], pos_[i2], end[i1], end[i2], column);
  CanonMotion m = move_to(CanonMotion::Kind::arc, end);
  Vec3 centre = end;
  centre[i1] = fit.c1;
  centre[i2] = fit.c2;
  m.centre_mm = program_to_machine(centre);
  m.plane = plane_ / 10;
  m.turn = fit.turn;
  if (inverse_time_) {  // LinuxCNC's find_arc_length: the radius at the start, turns, the helix's rise
    const double radius = std::hypot(pos_[i1] - fit.c1, pos_[i2] - fit.c2);
    const double alpha = std::atan2(pos_[i2] - fit.c2, pos_[i1] - fit.c1);
    double beta = std::atan2(end[i2] - fit.c2, end[i1] - fit.c1);
    double theta = 0.0;
    if (fit.turn > 0) {
      if (beta <= alpha) beta += 2.0 * std::numbers::pi;
      theta = beta - alpha + (fit.turn - 1) * 2.0 * std::numbers::pi;
    } else {
      double a = alpha;
      if (a <= beta) a += 2.0 * std::numbers::pi;
      theta = beta - a + (fit.turn + 1) * 2.0 * std::numbers::pi;
    }
    const double rise = end[ia] - pos_[ia];
    inverse_time_rate(block, rise == 0.0 ? radius * std::fabs(theta) : std::hypot(radius * theta, rise));
  }
  emit("ARC_FEED(" + num(end[i1]) + ", " + num(end[i2]) + ", " + num(fit.c1) + ", " + num(fit.c2) + ", " +
       std::to_string(fit.turn) + ", " + num(end[ia]) + ", 0.0000, 0.0000, 0.0000)", m);
  pos_ = canon_pos_ = end;
}

CanonMachine::ArcFit CanonMachine::arc_fit(const NgcBlock& block, bool clockwise, double s1, double s2, double e1,
                                           double e2, int column) const {
  char l1 = 'i', l2 = 'j';  // the centre's offset letters in this plane
  if (plane_ == 180) { l1 = 'k'; l2 = 'i'; }
  if (plane_ == 190) { l1 = 'j'; l2 = 'k'; }
  double c1 = 0.0, c2 = 0.0;
  const double tolerance_mm = unit_mm_ == 1.0 ? 0.005 : 0.0005 * kMmPerInch;
  if (block.has('r')) {
    if (block.has(l1) || block.has(l2)) throw NgcError(block.column('r'), "R with I/J/K: give one arc form");
    const double radius = length(block.value('r'));
    if (std::fabs(e1 - s1) < 1e-12 && std::fabs(e2 - s2) < 1e-12)
      throw NgcError(block.column('r'), "zero-length arc with the R form");
    const double abs_radius = std::fabs(radius);
    const double m1 = 0.5 * (s1 + e1), m2 = 0.5 * (s2 + e2);
    double half = std::hypot(m1 - e1, m2 - e2);
    if (half / abs_radius > 1.0 + 1e-12) throw NgcError(block.column('r'), "arc radius R too small to reach the end point");
    if (half / abs_radius > 1.0 - 1e-12) half = abs_radius;
    const double turn = clockwise ? -1.0 : 1.0;
    const double theta = std::atan2(e2 - s2, e1 - s1) +
                         (((turn > 0 && radius > 0) || (turn < 0 && radius < 0)) ? 0.5 : -0.5) * std::numbers::pi;
    const double offset = abs_radius * std::cos(std::asin(half / abs_radius));
    c1 = m1 + offset * std::cos(theta);
    c2 = m2 + offset * std::sin(theta);
  } else {
    if (!block.has(l1) && !block.has(l2)) throw NgcError(column, "arc needs an offset (I/J/K) or a radius R");
    if (arc_absolute_) {
      c1 = block.has(l1) ? length(block.value(l1)) : s1;
      c2 = block.has(l2) ? length(block.value(l2)) : s2;
    } else {
      c1 = s1 + length(block.value(l1));
      c2 = s2 + length(block.value(l2));
    }
    const double r1 = std::hypot(s1 - c1, s2 - c2), r2 = std::hypot(e1 - c1, e2 - c2);
    if (r1 < tolerance_mm || r2 < tolerance_mm) throw NgcError(column, "zero-radius arc");
    const double err = std::fabs(r1 - r2);
    if (err > tolerance_mm && err > 0.001 * r1)
      throw NgcError(column, "radius to the end of the arc differs from the radius to its start");
  }
  int turns = 1;
  if (block.has('p')) {
    const double p = block.value('p');
    if (p < 1.0 || std::floor(p) != p) throw NgcError(block.column('p'), "arc turns P must be a whole number >= 1");
    turns = static_cast<int>(std::fmin(p, 1e6));
  }
  return ArcFit{c1, c2, clockwise ? -turns : turns};
}

// G5.1: a quadratic B-spline in XY from here to X Y with the control point
// at I J from here. rs274 prints it as NURBS_FEED(3, ...) without its
// points, so only the checks and the end point are compared. Its canon is
// left at X0 Y0 (Z unchanged) in program coordinates, which is where a
// later M6 takes the position back from and a probe backs off toward.
void CanonMachine::spline(const NgcBlock& block, const Vec3& to, int column) {
  if (plane_ != 170) throw NgcError(column, "G5.1 splines only in the XY plane (G17)");
  comp_refuse(comp_side_ != 0, column, "use G5.1 splines");
  if (block.has('z')) throw NgcError(block.column('z'), "G5.1 splines may not move Z");
  if (!block.has('x') && !block.has('y') && !block.polar_radius && !block.polar_angle)
    throw NgcError(column, "G5.1 needs an end point (X, Y)");
  if (!block.has('i') || !block.has('j'))
    throw NgcError(block.has('i') ? block.column('i') : block.has('j') ? block.column('j') : column,
                   "G5.1 needs both I and J (the control point)");
  if (inverse_time_) throw NgcError(column, "G5.1 splines in inverse-time feed (G93) are not supported: G94 and an F first");
  if (feed_ <= 0.0) throw NgcError(column, "cannot do G5.1 with zero feed rate (F)");
  emit("NURBS_FEED(3, ...)", move_to(CanonMotion::Kind::spline, to));
  pos_ = to;
  canon_pos_[0] = canon_pos_[1] = 0.0;  // what rs274's canon is left at (a later M6 or probe starts there)
}

// G38.2-G38.5 as the standalone rs274 models them, with no probe input:
// the probe never trips and the move reaches its end; the position is then
// that end backed off 0.010 inch (0.254 mm) toward the start (the last point
// the canon moved to); #5061-#5063 hold the end in the program's units,
// #5064-#5069 zero and #5070 (tripped) 0.
void CanonMachine::probe(int motion, const Vec3& to, int column) {
  comp_refuse(comp_side_ != 0, column, "probe (G38.x)");
  if (inverse_time_) throw NgcError(column, "probe moves (G38.x) in inverse-time feed (G93): G94 and an F first");
  if (feed_ <= 0.0) throw NgcError(column, "cannot probe with zero feed rate (F)");
  // G38.2/G38.4 (an error if the probe does not change) need a move; G38.3/G38.5 may stay put.
  if ((motion == 382 || motion == 384) && to == pos_)
    throw NgcError(column, g_text(motion) + " move of zero length: the start point is the probe point");
  const Vec3 probe_from = pos_;
  emit("TURN_PROBE_ON()");
  CanonMotion move = move_to(CanonMotion::Kind::probe, to);
  move.value = motion - 380;  // 2..5: G38.2..G38.5
  emit("STRAIGHT_PROBE(" + xyz(to) + ")", move);
  emit("TURN_PROBE_OFF()");
  if (setup_.probe_input && !muted_) return probe_on_machine(move, to, column);
  for (int a = 0; a < 9; ++a)
    params_.set(ngc_number::kProbeResult + a, a < 3 ? to[static_cast<std::size_t>(a)] / unit_mm_ : 0.0, column);
  params_.set(ngc_number::kProbeTripped, 0.0, column);
  // Backed off toward where the canon last moved to (X0 Y0 after a G5.1 spline).
  const Vec3& from = canon_pos_;
  const double distance = std::hypot(from[0] - to[0], from[1] - to[1], from[2] - to[2]);
  constexpr double kBackoffMm = 0.010 * kMmPerInch;
  Vec3 end = to;
  if (distance > 0.0)
    for (std::size_t a = 0; a < 3; ++a) end[a] += kBackoffMm * (from[a] - to[a]) / distance;
  pos_ = canon_pos_ = end;
  if (muted_) skip_probe(probe_from, to);  // after the results' set: they stay unknown
}

// A probe run on the machine, as LinuxCNC's task does after it:
// #5061-#5063 where it tripped, in the program's coordinates and units at
// the time of the probe; without a trip (G38.3/G38.5) the programmed end;
// #5064-#5069 zero (no such axes), #5070 1 if it tripped. The program goes
// on from where the machine rests.
void CanonMachine::probe_on_machine(const CanonMotion& move, const Vec3& to, int column) {
  CanonCall call;
  call.line = line_;
  call.file = file_;
  call.motion = move;
  const ProbeRun run = setup_.probe_input(call);
  if (!run.error.empty()) throw NgcError(column, run.error);
  const Vec3 at = run.tripped ? machine_to_program(run.trip_mm) : to;
  for (int a = 0; a < 9; ++a) params_.set(ngc_number::kProbeResult + a, a < 3 ? at[static_cast<std::size_t>(a)] / unit_mm_ : 0.0, column);
  params_.set(ngc_number::kProbeTripped, run.tripped ? 1.0 : 0.0, column);
  pos_ = canon_pos_ = machine_to_program(run.rest_mm);
}

// G33.1: the spindle drives Z to the end and back at K per turn; the
// position afterwards is where the tap started (LinuxCNC's RIGID_TAP).
void CanonMachine::rigid_tap(const NgcBlock& block, const Vec3& to, int column) {
  comp_refuse(comp_side_ != 0, column, "use G33.1 rigid tapping");
  if (!block.has('k')) throw NgcError(column, "G33.1 needs K (the thread pitch, distance per spindle turn)");
  if (block.has('f')) throw NgcError(block.column('f'), "F with G33.1: the spindle sets the feed (K per turn)");
  if (spindle_ != 3 && spindle_ != 4) throw NgcError(column, "spindle not turning in G33.1 (M3 or M4 first)");
  char buf[64];
  std::snprintf(buf, sizeof buf, "START_SPEED_FEED_SYNC(%f,0)", block.value('k'));
  emit(buf);
  emit("RIGID_TAP(" + num(to[0]) + ", " + num(to[1]) + ", " + num(to[2]) + ")", move_to(CanonMotion::Kind::rigid_tap, to));
  emit("STOP_SPEED_FEED_SYNCH()");
}

void CanonMachine::emit_control_mode() {
  if (control_ == 610) emit("SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)");
  else if (control_ == 611) emit("SET_MOTION_CONTROL_MODE(CANON_EXACT_STOP)");
  else {
    emit("SET_MOTION_CONTROL_MODE(CANON_CONTINUOUS, " + fixed(control_p_, 6) + ")");
    emit("SET_NAIVECAM_TOLERANCE(" + fixed(control_q_, 4) + ")");
  }
}

void CanonMachine::set_origin(int index) {
  const Vec3 old = g5x_;
  origin_ = index;
  for (int a = 0; a < 3; ++a) g5x_[static_cast<std::size_t>(a)] = params_.get(ngc_number::kG5xBase + 20 * (index - 1) + a, 1);
  for (std::size_t a = 0; a < 3; ++a) {
    pos_[a] += old[a] - g5x_[a];
    canon_pos_[a] += old[a] - g5x_[a];
  }
  params_.set(ngc_number::kG5xSelected, index, 1);
}

void CanonMachine::program_end(bool m30) {
  set_origin(1);
  emit_g5x();
  emit("SET_XY_ROTATION(0.0000)");
  if (plane_ != 170) {
    plane_ = 170;
    emit("SELECT_PLANE(CANON_PLANE_XY)");
  }
  absolute_ = true;
  comp_side_ = 0;
  comp_first_ = true;
  inverse_time_ = false;
  emit("SET_FEED_MODE(0, 0)");
  feed_ = 0.0;
  emit("SET_FEED_RATE(0.0000)", valued(CanonMotion::Kind::feed_rate, 0.0));
  spindle_ = 5;
  emit("STOP_SPINDLE_TURNING(0)", valued(CanonMotion::Kind::spindle_stop, 1.0));  // 1: the program's end
  emit("SET_SPINDLE_MODE(0 0.0000)");
  if (mist_) emit("MIST_OFF()");
  if (flood_) emit("FLOOD_OFF()");
  mist_ = flood_ = false;
  motion_ = 10;
  if (m30) emit("PALLET_SHUTTLE()");
  emit("PROGRAM_END()", kind_only(CanonMotion::Kind::end));
  ended_ = true;
}

void CanonMachine::check_words(const NgcBlock& block, int motion, int non_modal) const {
  for (char c : {'a', 'b', 'c', 'u', 'v', 'w'})
    if (block.has(c))
      throw NgcError(block.column(c), std::string("unsupported word ") + static_cast<char>(std::toupper(c)) +
                                          " (this machine has X, Y and Z)");
  const bool comp_on = has_code(block.g, 410) || has_code(block.g, 420) || has_code(block.g, 411) || has_code(block.g, 421);
  if (block.has('d') && !comp_on) throw NgcError(block.column('d'), "word D with no G41, G42, G41.1 or G42.1 to use it");
  const bool arc = motion == 20 || motion == 30;
  const bool cycle = is_cycle(motion);
  for (char c : {'i', 'j', 'k'})
    if (block.has(c) && !arc && !(c == 'k' && motion == 331) && !(c != 'k' && (motion == 51 || non_modal == 100)) && motion != 870)
      throw NgcError(block.column(c), std::string("word ") + static_cast<char>(std::toupper(c)) + " with no G2, G3 or G87 to use it");
  if (block.has('r') && !arc && !cycle && non_modal != 100)
    throw NgcError(block.column('r'), "word R with no G2 or G3 to use it");
  if (block.has('l') && non_modal != 100 && !cycle && !has_code(block.g, 411) && !has_code(block.g, 421))
    throw NgcError(block.column('l'), "word L with no G10, G41.1, G42.1 or canned cycle to use it");
  if (block.has('h') && !has_code(block.g, 430)) throw NgcError(block.column('h'), "word H with no G43 to use it");
  if (block.has('q') && !has_code(block.g, 640) && motion != 830 && motion != 730 && non_modal != 100)
    throw NgcError(block.column('q'), "word Q with no G10, G64, G73 or G83 to use it");
  const bool cycle_dwell = motion == 820 || motion == 840 || motion == 860 || motion == 880 || motion == 890;
  if (block.has('p') && !(non_modal == 40 || non_modal == 100 || arc || cycle_dwell || has_code(block.g, 640)))
    throw NgcError(block.column('p'), "word P with no G4, G10, G64, arc or G82/G84/G86/G88/G89 to use it");
}

void CanonMachine::execute(const NgcBlock& block, int line) {
  line_ = line;
  started_ = true;
  if (modal_state_code(block)) return;
  // Modal groups: at most one G-code and M-code of each.
  std::array<const NgcCode*, 16> g_by_group{};
  for (const NgcCode& g : block.g) {
    const int group = g_group(g.code);
    if (group < 0) throw NgcError(g.column, unsupported_g(g.code));
    if (g_by_group[static_cast<std::size_t>(group)])
      throw NgcError(g.column, "two G-codes from one modal group (" + g_text(g_by_group[static_cast<std::size_t>(group)]->code) +
                                   " and " + g_text(g.code) + ")");
    g_by_group[static_cast<std::size_t>(group)] = &g;
  }
  std::array<const NgcCode*, 10> m_by_group{};
  for (const NgcCode& m : block.m) {
    const int group = m_group(m.code);
    if (group < 0) throw NgcError(m.column, "unsupported M-code M" + std::to_string(m.code));
    if (m_by_group[static_cast<std::size_t>(group)]) throw NgcError(m.column, "two M-codes from one modal group");
    m_by_group[static_cast<std::size_t>(group)] = &m;
  }
  const NgcCode* g_motion = g_by_group[1];
  const int non_modal = g_by_group[0] ? g_by_group[0]->code : -1;
  const bool axis_words = block.has('x') || block.has('y') || block.has('z') || block.polar_radius || block.polar_angle;
  const bool axis_consumer = non_modal == 100 || non_modal == 280 || non_modal == 300 || non_modal == 920 ||
                             (g_by_group[8] && g_by_group[8]->code == 431);  // G43.1 Z: an offset, not a move
  if (g_motion && axis_consumer)
    throw NgcError(g_motion->column, "a motion code and " + g_text(non_modal) + " on one line both use the axis words");
  int motion = g_motion ? g_motion->code : motion_;
  check_words(block, motion, non_modal);
  if (axis_words && !axis_consumer && motion == 800)
    throw NgcError(block.has('x') ? block.column('x') : block.has('y') ? block.column('y') : block.has('z') ? block.column('z') : 1,
                   "cannot use axis values without a G-code that uses them (G0, G1, G2, G3)");

  if ((block.polar_radius || block.polar_angle) && plane_ != 170)  // the plane before this line's G17
    throw NgcError(block.polar_radius ? block.polar_radius_column : block.polar_angle_column,
                   "polar @/^ only in the XY plane (G17)");

  apply_assignments(block);  // settings take effect after the line is read
  run_comments(block);
  if (const NgcCode* g = g_by_group[5]) {
    inverse_time_ = g->code == 930;
    if (inverse_time_) {  // the rate is set per move (inverse_time_rate); F keeps the last one
      emit("COMMENT(\"interpreter: feed mode set to inverse time\")");
      emit("SET_FEED_MODE(0, 0)");
    } else {
      emit("COMMENT(\"interpreter: feed mode set to units per minute\")");
      emit("SET_FEED_MODE(0, 0)");
      feed_ = 0.0;
      emit("SET_FEED_RATE(0.0000)", valued(CanonMotion::Kind::feed_rate, 0.0));
    }
  }
  if (block.has('f') && block.value('f') < 0.0) throw NgcError(block.column('f'), "negative feed rate F");
  if (block.has('f') && !inverse_time_) {
    feed_ = block.value('f');
    emit("SET_FEED_RATE(" + fixed(feed_, 4) + ")", valued(CanonMotion::Kind::feed_rate, feed_ * unit_mm_));
  }
  if (block.has('s')) {
    if (block.value('s') < 0.0) throw NgcError(block.column('s'), "negative spindle speed S");
    speed_ = block.value('s');
    emit("SET_SPINDLE_SPEED(0, " + fixed(speed_, 4) + ")", valued(CanonMotion::Kind::spindle_speed, speed_));
  }
  if (block.has('t')) {
    const int t = static_cast<int>(block.value('t'));
    if (t < 0) throw NgcError(block.column('t'), "negative tool number T");
    if (t != 0 && !tools_.find(t))
      throw NgcError(block.column('t'), "requested tool " + std::to_string(t) + " not found in the tool table");
    selected_tool_ = t;
    emit("SELECT_TOOL(" + std::to_string(t) + ")");
  }
  if (m_by_group[6]) {  // M6
    comp_refuse(comp_side_ != 0, m_by_group[6]->column, "change tools");
    emit("START_CHANGE()");
    emit("STOP_SPINDLE_TURNING(0)", kind_only(CanonMotion::Kind::spindle_stop));
    spindle_ = 5;
    tool_in_spindle_ = selected_tool_;
    emit("CHANGE_TOOL(" + std::to_string(tool_in_spindle_) + ")", valued(CanonMotion::Kind::tool_change, tool_in_spindle_));
  }
  if (const NgcCode* m = m_by_group[7]) {
    spindle_ = m->code;
    emit(m->code == 3 ? "START_SPINDLE_CLOCKWISE(0)" : m->code == 4 ? "START_SPINDLE_COUNTERCLOCKWISE(0)"
                                                                    : "STOP_SPINDLE_TURNING(0)",
         m->code == 5 ? kind_only(CanonMotion::Kind::spindle_stop)
                      : valued(CanonMotion::Kind::spindle_on, m->code == 3 ? 1.0 : -1.0));
  }
  if (const NgcCode* m = m_by_group[8]) {
    if (m->code == 7) { mist_ = true; emit("MIST_ON()", kind_only(CanonMotion::Kind::coolant_on)); }
    if (m->code == 8) { flood_ = true; emit("FLOOD_ON()", kind_only(CanonMotion::Kind::coolant_on)); }
    if (m->code == 9) { mist_ = flood_ = false; emit("MIST_OFF()"); emit("FLOOD_OFF()"); }
  }
  if (non_modal == 40) {
    if (!block.has('p')) throw NgcError(g_by_group[0]->column, "G4 needs P (seconds)");
    if (block.value('p') < 0.0) throw NgcError(block.column('p'), "negative dwell time P");
    emit("DWELL(" + fixed(block.value('p'), 4) + ")", valued(CanonMotion::Kind::dwell, block.value('p')));
  }
  if (const NgcCode* g = g_by_group[2]) {
    comp_refuse(comp_side_ != 0 && g->code != plane_, g->column, "change planes");
    plane_ = g->code;
    emit(g->code == 170 ? "SELECT_PLANE(CANON_PLANE_XY)" : g->code == 180 ? "SELECT_PLANE(CANON_PLANE_XZ)"
                                                                          : "SELECT_PLANE(CANON_PLANE_YZ)");
  }
  if (const NgcCode* g = g_by_group[6]) {
    unit_mm_ = g->code == 200 ? kMmPerInch : 1.0;
    emit(g->code == 200 ? "USE_LENGTH_UNITS(CANON_UNITS_INCHES)" : "USE_LENGTH_UNITS(CANON_UNITS_MM)");
  }
  if (const NgcCode* g = g_by_group[7]) {
    if (g->code == 400) comp_off(g->column);
    else comp_on(block, *g);
  }
  if (const NgcCode* g = g_by_group[8]) {
    comp_refuse(comp_side_ != 0, g->column, "change the tool length offset");
    Vec3 offset{};
    if (g->code == 430) {
      const int tool = block.has('h') ? static_cast<int>(block.value('h')) : tool_in_spindle_;
      if (tool < 0) throw NgcError(block.column('h'), "negative tool number H");
      if (tool != 0) {
        const ToolEntry* e = tools_.find(tool);
        if (!e) throw NgcError(block.has('h') ? block.column('h') : g->column, "tool " + std::to_string(tool) + " not in the tool table");
        offset = {e->offset[0], e->offset[1], e->offset[2]};
      }
    } else if (g->code == 431) {
      static constexpr char kAxes[3] = {'x', 'y', 'z'};
      for (std::size_t a = 0; a < 3; ++a)
        if (block.has(kAxes[a])) offset[a] = length(block.value(kAxes[a]));
    }
    for (std::size_t a = 0; a < 3; ++a) pos_[a] += tool_offset_[a] - offset[a];
    tool_offset_ = offset;
    tool_length_ = g->code;
    emit("USE_TOOL_LENGTH_OFFSET(" + num(offset[0]) + " " + num(offset[1]) + " " + num(offset[2]) +
         ", 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)");
  }
  if (const NgcCode* g = g_by_group[12]) {
    comp_refuse(comp_side_ != 0, g->column, "change coordinate systems");
    const int index = g->code <= 590 ? (g->code - 540) / 10 + 1 : 6 + (g->code - 590);
    if (index == origin_) {
      emit("COMMENT(\"interpreter: continuing to use same coordinate system\")");
    } else {
      set_origin(index);
      emit_g5x();
      emit_g92();
      emit("SET_XY_ROTATION(0.0000)");
    }
  }
  if (const NgcCode* g = g_by_group[13]) {
    comp_refuse(comp_side_ != 0, g->column, "change the path control mode");
    control_ = g->code;
    if (g->code == 640) {
      control_p_ = block.has('p') ? block.value('p') : 0.0;
      control_q_ = block.has('q') ? block.value('q') : control_p_;
      if (control_p_ < 0.0 || control_q_ < 0.0)
        throw NgcError(block.column(control_p_ < 0.0 ? 'p' : 'q'), "G64 tolerances P and Q must be >= 0");
    }
    emit_control_mode();
  }
  if (const NgcCode* g = g_by_group[3]) {
    const bool absolute = g->code == 900;
    if (absolute != absolute_)
      emit(absolute ? "COMMENT(\"interpreter: distance mode changed to absolute\")"
                    : "COMMENT(\"interpreter: distance mode changed to incremental\")");
    absolute_ = absolute;
  }
  if (const NgcCode* g = g_by_group[4]) {
    const bool absolute = g->code == 901;
    if (absolute != arc_absolute_)
      emit(absolute ? "COMMENT(\"interpreter: IJK distance mode changed to absolute\")"
                    : "COMMENT(\"interpreter: IJK distance mode changed to incremental\")");
    arc_absolute_ = absolute;
  }
  if (const NgcCode* g = g_by_group[10]) {  // G98/G99: the canned cycles' retract
    comp_refuse(comp_side_ != 0, g->column, "change the retract mode");
    retract_old_z_ = g->code == 980;
    emit(retract_old_z_ ? "COMMENT(\"interpreter: retract mode set to old_z\")"
                        : "COMMENT(\"interpreter: retract mode set to r_plane\")");
  }

  // Group 0: G10, G28/G30, G92 family (G4 ran above, G53 modifies the motion).
  const int g10_l = non_modal == 100 && block.has('l') ? static_cast<int>(block.value('l')) : -1;
  refuse_unknown_position(block, non_modal, g10_l, g_by_group[0] ? g_by_group[0]->column : 1);
  if (non_modal == 100 && g10_l != 1 && g10_l != 2 && g10_l != 10 && g10_l != 11 && g10_l != 20)
    throw NgcError(block.has('l') ? block.column('l') : g_by_group[0]->column, "G10 needs L1, L2, L10, L11 or L20");
  if (g10_l == 1 || g10_l == 10 || g10_l == 11) {
    setup_tool(block, g10_l, g_by_group[0]->column);
  } else if (non_modal == 100) {
    const int l = g10_l;
    for (char c : {'i', 'j', 'q'})
      if (block.has(c))
        throw NgcError(block.column(c), std::string("word ") + static_cast<char>(std::toupper(c)) + " with G10 L" +
                                            std::to_string(l) + " (I, J and Q are a tool's, for G10 L1, L10, L11)");
    if (!block.has('p')) throw NgcError(g_by_group[0]->column, "G10 L" + std::to_string(l) + " needs P (0 current, 1..9 G54..G59.3)");
    const double pv = block.value('p');
    if (pv < 0.0 || pv > 9.0 || std::floor(pv) != pv) throw NgcError(block.column('p'), "G10 P must be 0..9");
    if (block.has('r') && block.value('r') != 0.0) throw NgcError(block.column('r'), "G10 rotation R is not supported yet");
    const int system = pv == 0.0 ? origin_ : static_cast<int>(pv);
    comp_refuse(comp_side_ != 0 && system == origin_, g_by_group[0]->column, "change the active coordinate system");
    static constexpr char kAxes[3] = {'x', 'y', 'z'};
    for (std::size_t a = 0; a < 3; ++a) {
      if (!block.has(kAxes[a])) continue;
      const double v = length(block.value(kAxes[a]));
      const double offset = l == 2 ? v : pos_[a] + g5x_[a] - v;  // L20: here becomes v
      params_.set(ngc_number::kG5xBase + 20 * (system - 1) + static_cast<int>(a), offset, block.column(kAxes[a]));
    }
    if (system != origin_) {
      emit("COMMENT(\"interpreter: setting coordinate system origin\")");
    } else {
      set_origin(system);
      emit_g5x();
      emit("SET_XY_ROTATION(0.0000)");
    }
  } else if (non_modal == 280 || non_modal == 300) {
    comp_refuse(comp_side_ != 0, g_by_group[0]->column, "use G28 or G30");
    const Vec3 via = target(block, false);
    move_traverse(via);
    const int base = non_modal == 280 ? ngc_number::kG28Home : ngc_number::kG30Home;
    Vec3 home_machine{};
    for (int a = 0; a < 3; ++a) home_machine[static_cast<std::size_t>(a)] = params_.get(base + a, 1);
    const Vec3 home = machine_to_program(home_machine);
    Vec3 to = pos_;
    static constexpr char kAxes[3] = {'x', 'y', 'z'};
    for (std::size_t a = 0; a < 3; ++a)
      if (!axis_words || block.has(kAxes[a])) to[a] = home[a];
    move_traverse(to);
  } else if (non_modal == 281 || non_modal == 301) {
    const Vec3 m = program_to_machine(pos_);
    const int base = non_modal == 281 ? ngc_number::kG28Home : ngc_number::kG30Home;
    for (int a = 0; a < 3; ++a) params_.set(base + a, m[static_cast<std::size_t>(a)], 1);
  } else if (non_modal >= 920 && non_modal <= 923) {
    comp_refuse(comp_side_ != 0, g_by_group[0]->column, "change axis offsets (G92)");
  }
  if (non_modal == 920) {
    if (!axis_words) throw NgcError(g_by_group[0]->column, "G92 needs at least one axis word");
    static constexpr char kAxes[3] = {'x', 'y', 'z'};
    for (std::size_t a = 0; a < 3; ++a) {
      if (!block.has(kAxes[a])) continue;
      const double offset = pos_[a] + g92_[a] - length(block.value(kAxes[a]));
      pos_[a] += g92_[a] - offset;
      canon_pos_[a] += g92_[a] - offset;
      g92_[a] = offset;
    }
    for (int a = 0; a < 3; ++a) params_.set(ngc_number::kG92Base + a, g92_[static_cast<std::size_t>(a)], 1);
    params_.set(ngc_number::kG92Enabled, 1.0, 1);
    emit_g92();
  } else if (non_modal == 921 || non_modal == 922 || non_modal == 923) {
    Vec3 offset{};
    if (non_modal == 923)
      for (int a = 0; a < 3; ++a) offset[static_cast<std::size_t>(a)] = params_.get(ngc_number::kG92Base + a, 1);
    for (std::size_t a = 0; a < 3; ++a) {
      pos_[a] += g92_[a] - offset[a];
      canon_pos_[a] += g92_[a] - offset[a];
    }
    g92_ = offset;
    if (non_modal == 921)
      for (int a = 0; a < 3; ++a) params_.set(ngc_number::kG92Base + a, 0.0, 1);
    // #5210 says whether G92 is applied: G92.2 keeps the offsets but takes
    // them off (G10 L10 then measures without them), G92.3 puts them back.
    params_.set(ngc_number::kG92Enabled, non_modal == 923 ? 1.0 : 0.0, 1);
    emit_g92();
  }

  // Motion.
  // Where a run of canned cycles begins along the cycle's axis (Z in G17,
  // Y in G18, X in G19: the plane of this line, set above). One number, as
  // in rs274: a plane change within the run keeps it.
  if (g_motion && is_cycle(g_motion->code) && !is_cycle(motion_))
    cycle_start_z_ = pos_[plane_ == 170 ? 2 : plane_ == 180 ? 1 : 0];
  // A cycle's R, Z, P and Q carry over only while the same cycle goes on.
  cycle_continues_ = !g_motion || g_motion->code == motion_;
  if (g_motion && g_motion->code != 51) motion_ = g_motion->code;  // G5.1 leaves the motion mode as it was (as rs274 does)
  const bool machine = non_modal == 530;
  if (machine) {
    comp_refuse(comp_side_ != 0, g_by_group[0]->column, "use G53");
    if (!(motion == 0 || motion == 10)) throw NgcError(g_by_group[0]->column, "G53 needs G0 or G1");
    if (!absolute_) throw NgcError(g_by_group[0]->column, "G53 cannot be used in incremental distance mode (G91)");
  }
  if (g_motion && g_motion->code == 800) emit("COMMENT(\"interpreter: motion mode set to none\")");
  // A G0 or G1 without axis words still moves, to where it is (as rs274 does).
  const bool explicit_line = g_motion && (motion == 0 || motion == 10);
  if (is_probe(motion) && g_motion && !axis_words) throw NgcError(g_motion->column, "G38.x needs an axis word (X, Y, Z)");
  if (is_probe(motion) && axis_words && !axis_consumer && m_by_group[4])
    throw NgcError(m_by_group[4]->column, "a probe move (G38.x) and M" + std::to_string(m_by_group[4]->code) +
                                              " on one line (rs274 drops the M-code): give each its own line");
  if (motion == 51) {
    const Vec3 to = target(block, machine);
    spline(block, to, g_motion->column);
  } else if (is_probe(motion) && axis_words && !axis_consumer) {
    probe(motion, target(block, machine), g_motion ? g_motion->column : 1);
  } else if ((axis_words && !axis_consumer) || explicit_line ||
      (g_motion && (motion == 20 || motion == 30) && !axis_consumer &&
       (block.has('i') || block.has('j') || block.has('k') || block.has('r')))) {
    const Vec3 to = target(block, machine);
    const int column = g_motion ? g_motion->column : 1;
    if (motion == 10 && inverse_time_) {
      if (!block.has('f')) throw NgcError(column, "inverse-time feed (G93): G1 needs its own F on its line");
      // From the programmed point once compensation has entered (the extra corner arc is not counted), as LinuxCNC.
      const Vec3& from = comp_active() && !comp_first_ ? programmed_ : pos_;
      constexpr double kTinyProgramUnits = 1e-7;  // LinuxCNC's find_straight_length: no move below it
      bool moves = false;
      for (std::size_t a = 0; a < 3; ++a) moves = moves || std::fabs(to[a] - from[a]) > kTinyProgramUnits * unit_mm_;
      inverse_time_rate(block, moves ? std::hypot(to[0] - from[0], to[1] - from[1], to[2] - from[2]) : 0.0);
    }
    if ((motion == 0 || motion == 10) && comp_active()) {
      if (motion == 10 && feed_ <= 0.0) throw NgcError(column, "cannot do G1 with zero feed rate (F)");
      arc_not_allowed_ = false;
      comp_straight(motion, to, column);
    } else if (motion == 0 || motion == 10) {
      arc_not_allowed_ = false;
      if (motion == 0) move_traverse(to);
      else move_feed(to, column);
    }
    else if (motion == 20 || motion == 30) arc(block, motion == 20, to, column);
    else if (motion == 331) rigid_tap(block, to, column);
    else if (is_cycle(motion)) {
      comp_refuse(comp_side_ != 0, column, "use canned cycles");
      if (inverse_time_) throw NgcError(column, "canned cycles in inverse-time feed (G93): G94 and an F first");
      canned_cycle(block, motion, column);
    }
  }

  learn_position(block, motion, non_modal, axis_words && !axis_consumer);

  // After a tool change LinuxCNC takes its position back from the machine
  // (the last point moved to, shifted by offset changes but not by a new
  // tool length offset, which moves nothing until the next move).
  if (m_by_group[6]) pos_ = canon_pos_;

  if (const NgcCode* m = m_by_group[4]) {
    comp_column_ = m->column;
    comp_flush_here();
    if (m->code == 0) emit("PROGRAM_STOP()", kind_only(CanonMotion::Kind::pause));
    else if (m->code == 1) emit("OPTIONAL_PROGRAM_STOP()", valued(CanonMotion::Kind::pause, 1.0));
    else if (m->code == 60) {  // pallet change: the shuttle, then a program stop (60: the pause's reason)
      emit("PALLET_SHUTTLE()");
      emit("PROGRAM_STOP()", valued(CanonMotion::Kind::pause, 60.0));
    } else program_end(m->code == 30);
  }
}

}  // namespace tnv::gcode
