// Cutter radius compensation (G40, G41, G42, G41.1, G42.1) in the XY plane
// (and XZ, for lathe tools) with LinuxCNC's geometry, so the calls match its
// rs274 call by call (docs/gcode.md "Cutter radius compensation"):
// - the entry move (the first after G41/G42) ends one radius to the side of
//   its programmed end, square to the move; an entry shorter than the radius
//   is an error;
// - each later move waits in a queue until the next one is known. At a
//   convex corner an arc around the programmed corner is inserted; at a
//   concave one the waiting move's end is pulled back to where the tool
//   touches both, and a move that would have to run backwards for that (the
//   tool does not fit: it would gouge) is an error;
// - G40 ends the queue where the tool is; the next move (the exit move) goes
//   from there to the programmed point and must be straight.
// Angles and tolerances are LinuxCNC's (0.05 rad for a corner, 1e-4 equal).
#include <cmath>
#include <numbers>

#include "tools/gcode/canon_state.hpp"
#include "tools/gcode/ngc_error.hpp"

namespace tnv::gcode {

namespace {

constexpr double kCompPi = std::numbers::pi;
constexpr double kCompHalfPi = std::numbers::pi / 2.0;
constexpr double kCompCornerTolerance = 0.05;  // radians: straighter than this is no corner
constexpr double kCompEqualTolerance = 1e-4;
constexpr int kCompLeft = 1, kCompRight = 2;

// The tool runs inside the arc's circle: left of a counterclockwise arc, right of a clockwise one.
bool tool_inside_arc(int side, int turn) { return (side == kCompLeft && turn > 0) || (side == kCompRight && turn < 0); }

// The signed angle swept from (x1, y1) to (x2, y2) around the centre, going
// `turn` times (> 0 counterclockwise); a point back where it started is a full turn.
double swept_angle(double x1, double y1, double cx, double cy, int turn, double x2, double y2) {
  if (turn == 0) return 0.0;
  double from = std::atan2(y1 - cy, x1 - cx);
  double to = std::atan2(y2 - cy, x2 - cx);
  if (turn > 0) {
    if (to <= from) to += 2.0 * kCompPi;
    return to - from + (turn - 1) * 2.0 * kCompPi;
  }
  if (from <= to) from += 2.0 * kCompPi;
  return to - from + (turn + 1) * 2.0 * kCompPi;
}

}  // namespace

void CanonMachine::comp_refuse(bool refused, int column, const std::string& what) const {
  if (refused) throw NgcError(column, "cannot " + what + " with cutter radius compensation on (G41/G42; G40 first)");
}

void CanonMachine::comp_on(const NgcBlock& block, const NgcCode& g) {
  const bool left = g.code == 410 || g.code == 411;
  const std::string name = g.code == 410 ? "G41" : g.code == 420 ? "G42" : g.code == 411 ? "G41.1" : "G42.1";
  if (plane_ != 170 && plane_ != 180) throw NgcError(g.column, name + " only in the XY (G17) or XZ (G18) plane");
  if (comp_side_ != 0) throw NgcError(g.column, "cannot turn cutter radius compensation on when it is already on");
  double radius = 0.0;  // mm; negative swaps the side
  int orientation = 0;
  if (g.code == 411 || g.code == 421) {
    if (!block.has('d')) throw NgcError(g.column, name + " needs D (the tool diameter)");
    if (block.has('l') && plane_ != 180)
      throw NgcError(block.column('l'), name + " with L (a lathe tool orientation) needs the XZ plane (G18)");
    radius = length(block.value('d')) / 2.0;
    if (block.has('l')) orientation = static_cast<int>(block.value('l'));
  } else {
    int tool = tool_in_spindle_;
    if (block.has('d')) {
      const double d = block.value('d');
      const double whole = std::floor(d + 0.5);
      if (std::fabs(d - whole) >= 1e-4) throw NgcError(block.column('d'), name + " needs D to be a whole number (a tool)");
      if (whole < 0.0) throw NgcError(block.column('d'), "negative D word (tool radius index)");
      if (whole != 0.0) tool = static_cast<int>(std::fmin(whole, 2e9));
    }
    if (tool != 0) {
      const ToolEntry* e = tools_.find(tool);
      if (!e) throw NgcError(block.has('d') ? block.column('d') : g.column, "requested tool " + std::to_string(tool) + " not found in the tool table");
      if (plane_ != 180 && e->orientation != 0 && e->orientation != 9)
        throw NgcError(g.column, name + " with a lathe tool (orientation " + std::to_string(e->orientation) + ") needs the XZ plane (G18)");
      radius = e->diameter / 2.0;
      orientation = e->orientation;
    }
  }
  int side = left ? kCompLeft : kCompRight;
  if (radius < 0.0) {  // a negative diameter (a worn-under tool) cuts on the other side
    radius = -radius;
    side = side == kCompLeft ? kCompRight : kCompLeft;
  }
  emit(side == kCompRight ? "COMMENT(\"interpreter: cutter radius compensation on right\")"
                      : "COMMENT(\"interpreter: cutter radius compensation on left\")");
  comp_side_ = side;
  comp_line_ = line_;
  comp_radius_ = radius;
  comp_orientation_ = orientation;
  comp_first_ = true;
  if (plane_ == 170) {
    comp_a1_ = 0, comp_a2_ = 1, comp_a3_ = 2;
  } else {
    comp_a1_ = 2, comp_a2_ = 0, comp_a3_ = 1;
  }
}

// A lathe tool's origin is not the centre of its nose radius, which
// compensation steers: LinuxCNC moves the printed point by the radius
// towards the origin for orientations 1..8 in G18.
CanonMachine::Vec3 CanonMachine::lathe_origin(const Vec3& v) const {
  Vec3 out = v;
  if (plane_ != 180) return out;
  const int o = comp_orientation_;
  const double r = comp_radius_;
  if (o == 2 || o == 6 || o == 1) out[0] -= r;
  if (o == 3 || o == 8 || o == 4) out[0] += r;
  if (o == 2 || o == 7 || o == 3) out[2] -= r;
  if (o == 1 || o == 5 || o == 4) out[2] += r;
  return out;
}

void CanonMachine::comp_off(int column) {
  comp_column_ = column;
  emit("COMMENT(\"interpreter: cutter radius compensation off\")");
  if (comp_active()) {
    comp_flush_here();
    canon_pos_ = pos_;
    tool_after_g40_machine_ = program_to_machine(pos_);
    pos_ = programmed_;
    arc_not_allowed_ = true;
  }
  comp_side_ = 0;
  comp_first_ = true;
}

void CanonMachine::comp_flush_here() {
  move_endpoint_and_flush(first(pos_), second(pos_));
  dequeue();
}

void CanonMachine::print_queued(const Queued& q) {
  if (q.kind != Queued::Kind::text) tool_after_g40_machine_.reset();
  if (muted_) return;
  const int line = line_;
  line_ = q.line;
  switch (q.kind) {
    case Queued::Kind::text: sink_(CanonCall{line_, q.text, q.motion, q.file}); break;
    case Queued::Kind::traverse: {
      const Vec3 end = lathe_origin(q.end);
      sink_(CanonCall{line_, "STRAIGHT_TRAVERSE(" + xyz(end) + ")", move_to(CanonMotion::Kind::traverse, end), q.file});
      break;
    }
    case Queued::Kind::feed: {
      const Vec3 end = lathe_origin(q.end);
      sink_(CanonCall{line_, "STRAIGHT_FEED(" + xyz(end) + ")", move_to(CanonMotion::Kind::feed, end), q.file});
      break;
    }
    case Queued::Kind::arc: {
      const Vec3 end = lathe_origin(q.end);
      const Vec3 centre = lathe_origin(point(q.c1, q.c2, 0.0));
      CanonMotion m = move_to(CanonMotion::Kind::arc, end);
      m.centre_mm = program_to_machine(point(first(centre), second(centre), third(end)));
      m.plane = plane_ / 10;
      m.turn = q.turn;
      sink_(CanonCall{line_, "ARC_FEED(" + num(first(end)) + ", " + num(second(end)) + ", " + num(first(centre)) + ", " +
                                   num(second(centre)) + ", " + std::to_string(q.turn) + ", " + num(third(end)) +
                                   ", 0.0000, 0.0000, 0.0000)", m, q.file});
      break;
    }
  }
  line_ = line;
}

void CanonMachine::dequeue() {
  endpoint_valid_ = false;
  for (const Queued& q : queue_) print_queued(q);
  queue_.clear();
}

void CanonMachine::enqueue_line(int motion, double dx, double dy, const Vec3& end) {
  Queued q;
  q.kind = motion == 0 ? Queued::Kind::traverse : Queued::Kind::feed;
  q.line = line_;
  q.file = file_;
  q.dx = dx;
  q.dy = dy;
  q.end = end;
  queue_.push_back(q);
}

void CanonMachine::enqueue_arc(double sweep, double e1, double e2, double c1, double c2, int turn, double e3) {
  Queued q;
  q.kind = Queued::Kind::arc;
  q.line = line_;
  q.file = file_;
  q.end = point(e1, e2, e3);
  q.c1 = c1;
  q.c2 = c2;
  q.turn = turn;
  q.sweep = sweep;
  queue_.push_back(q);
}

// Every queued move now ends at (x, y); a line that would then run against
// its programmed direction, or an arc that would sweep further than it was
// programmed to, means the tool cannot reach the corner without gouging.
void CanonMachine::move_endpoint_and_flush(double x, double y) {
  if (queue_.empty()) return;
  for (Queued& q : queue_) {
    if (q.kind == Queued::Kind::arc) {
      const double r1 = std::hypot(first(q.end) - q.c1, second(q.end) - q.c2);
      const double r2 = std::hypot(x - q.c1, y - q.c2);
      const double sweep = swept_angle(endpoint_[0], endpoint_[1], q.c1, q.c2, q.turn, x, y);
      if (std::fabs(r1 - r2) > 0.01 * unit_mm_)
        throw NgcError(comp_column_, "cutter radius compensation made an arc whose radii do not match (an interpreter bug)");
      // The margin is an angle, yet rs274 (Debian's 2.9) takes 0.001 in an inch
      // program and 0.0254 in a millimetre one: the same here, so both refuse alike.
      const double margin = unit_mm_ == 1.0 ? 0.0254 : 0.001;
      if (q.sweep != 0.0 && endpoint_valid_ && std::fabs(sweep) > std::fabs(q.sweep) + margin)
        throw NgcError(comp_column_, "arc move in a concave corner cannot be reached by the tool without gouging "
                          "(the tool is too large for the corner)");
      first(q.end) = x;
      second(q.end) = y;
    } else if (q.kind != Queued::Kind::text) {
      const double dot = q.dx * (x - endpoint_[0]) + q.dy * (y - endpoint_[1]);
      if (endpoint_valid_ && dot < 0.0)
        throw NgcError(comp_column_, std::string(q.kind == Queued::Kind::traverse ? "straight traverse" : "straight feed") +
                              " in a concave corner cannot be reached by the tool without gouging "
                              "(the tool is too large for the corner)");
      first(q.end) = x;
      second(q.end) = y;
    }
  }
  dequeue();
  set_endpoint(x, y);
}

void CanonMachine::comp_straight(int motion, const Vec3& to, int column) {
  comp_column_ = column;
  if (comp_first_) comp_line_first(motion, to);
  else comp_line_next(motion, to);
  canon_pos_ = pos_;
}

// The entry move: from the tool's centre to one radius beside the
// programmed end, square to the line from here to there.
void CanonMachine::comp_line_first(int motion, const Vec3& p) {
  const double cx = first(pos_), cy = second(pos_);
  if (std::hypot(first(p) - cx, second(p) - cy) <= comp_radius_)
    throw NgcError(comp_column_, "the cutter radius compensation entry move is not longer than the tool radius");
  const double alpha = std::atan2(second(p) - cy, first(p) - cx) + (comp_side_ == kCompLeft ? kCompHalfPi : -kCompHalfPi);
  const Vec3 end = point(first(p) + comp_radius_ * std::cos(alpha), second(p) + comp_radius_ * std::sin(alpha), third(p));
  set_endpoint(cx, cy);
  enqueue_line(motion, std::cos(alpha), std::sin(alpha), end);
  comp_first_ = false;
  pos_ = end;
  programmed_ = p;
}

void CanonMachine::comp_line_next(int motion, const Vec3& p) {
  const double cx = first(pos_), cy = second(pos_);
  const double opx = first(programmed_), opy = second(programmed_);
  Vec3 end = point(cx, cy, third(p));
  if (first(p) == opx && second(p) == opy) {  // no XY motion: it waits with the move before it
    enqueue_line(motion, 0.0, 0.0, end);
  } else {
    const double radius = comp_radius_;
    const bool left = comp_side_ == kCompLeft;
    double theta = std::atan2(cy - opy, cx - opx);  // from the programmed point to the tool
    double alpha = std::atan2(second(p) - opy, first(p) - opx);  // the new move's direction
    double beta = 0.0;                              // how far the path turns away from the tool's side
    if (left) {
      if (theta < alpha) theta += 2.0 * kCompPi;
      beta = theta - alpha - kCompHalfPi;
    } else {
      if (alpha < theta) alpha += 2.0 * kCompPi;
      beta = alpha - theta - kCompHalfPi;
    }
    const double gamma = left ? kCompHalfPi : -kCompHalfPi;
    first(end) = first(p) + radius * std::cos(alpha + gamma);
    second(end) = second(p) + radius * std::sin(alpha + gamma);
    const double mid_x = opx + radius * std::cos(alpha + gamma);
    const double mid_y = opy + radius * std::sin(alpha + gamma);
    const bool front_is_arc = !queue_.empty() && queue_.front().kind == Queued::Kind::arc;
    bool concave = beta < -kCompCornerTolerance || beta > kCompPi + kCompCornerTolerance;
    // An "h": off a round top onto a straight with the tool on the outside
    // of both; LinuxCNC stays above the corner rather than loop around.
    if (!concave && beta > kCompPi - kCompCornerTolerance && front_is_arc &&
        ((!left && queue_.front().turn > 0) || (left && queue_.front().turn < 0)))
      concave = true;
    if (!concave && beta > kCompCornerTolerance) {  // convex: round the programmed corner
      move_endpoint_and_flush(cx, cy);
      if (motion == 10) {
        enqueue_arc(0.0, mid_x, mid_y, opx, opy, left ? -1 : 1, third(pos_));
      } else {
        // No rapid arc: a straight traverse to where the arc would end.
        enqueue_line(0, 0.0, 0.0, point(mid_x, mid_y, third(pos_)));
      }
      dequeue();
      set_endpoint(mid_x, mid_y);
    } else if (concave) {
      if (!front_is_arc) {  // line to line: back off along the last move
        const double half_corner = (beta + kCompPi) / 2.0;
        if (half_corner == 0.0) throw NgcError(comp_column_, "a zero-degree inside corner cannot be cut with cutter radius compensation");
        const double retreat = radius / std::tan(half_corner);
        move_endpoint_and_flush(cx + retreat * std::cos(theta + gamma), cy + retreat * std::sin(theta + gamma));
      } else {  // arc to line: where the compensated arc meets the offset line
        const Queued& prev = queue_.front();
        const double old_radius = std::hypot(prev.c2 - second(prev.end), prev.c1 - first(prev.end));
        const double base_dir = std::atan2(second(p) - opy, first(p) - opx);
        const double normal = prev.turn > 0 ? base_dir + kCompHalfPi : base_dir - kCompHalfPi;
        const double phi = std::atan2(prev.c2 - opy, prev.c1 - opx);
        const bool inside = tool_inside_arc(comp_side_, prev.turn);
        const double programmed_radius = inside ? old_radius + radius : old_radius - radius;
        const double d = programmed_radius * std::cos(normal - phi);  // old centre to the new line
        const double l = (inside ? d - radius : d + radius) / old_radius;
        if (l > 1.0 || l < -1.0)
          throw NgcError(comp_column_, "an arc then a straight make a corner the compensated tool cannot fit in without gouging");
        const double turn_sign = (prev.turn > 0) == inside ? -1.0 : 1.0;
        const double angle = turn_sign * std::acos(l) + normal + kCompPi;
        move_endpoint_and_flush(prev.c1 + old_radius * std::cos(angle), prev.c2 + old_radius * std::sin(angle));
      }
    } else {  // straight on (or tangent from an arc)
      dequeue();
      set_endpoint(cx, cy);
    }
    enqueue_line(motion, first(p) - opx, second(p) - opy, end);
  }
  pos_ = end;
  programmed_ = p;
}

void CanonMachine::comp_arc(const NgcBlock& block, bool clockwise, const Vec3& end, int column) {
  comp_column_ = column;
  if (comp_first_) comp_arc_first(block, clockwise, end, column);
  else {
    const double opx = first(programmed_), opy = second(programmed_);
    const double cx = first(pos_), cy = second(pos_);
    const ArcFit fit = arc_fit(block, clockwise, opx, opy, first(end), second(end), column);
    const int side = comp_side_;
    const double radius = comp_radius_;
    const double arc_radius = std::hypot(fit.c1 - first(end), fit.c2 - second(end));
    double theta = std::atan2(cy - opy, cx - opx);
    theta = side == kCompLeft ? theta - kCompHalfPi : theta + kCompHalfPi;  // the direction the tool was going
    double delta = std::atan2(fit.c2 - opy, fit.c1 - opx);
    const double alpha = clockwise ? delta + kCompHalfPi : delta - kCompHalfPi;  // the arc's direction at its start
    double beta = side == kCompLeft ? theta - alpha : alpha - theta;
    beta = beta > 1.5 * kCompPi ? beta - 2.0 * kCompPi : beta < -kCompHalfPi ? beta + 2.0 * kCompPi : beta;
    double gamma = 0.0;
    const bool inside = (side == kCompLeft && !clockwise) || (side == kCompRight && clockwise);
    if (inside) {
      gamma = std::atan2(fit.c2 - second(end), fit.c1 - first(end));
      if (arc_radius <= radius)
        throw NgcError(column, "the tool radius is not less than the arc's radius with cutter radius compensation");
    } else {
      gamma = std::atan2(second(end) - fit.c2, first(end) - fit.c1);
      delta += kCompPi;
    }
    const double new_x = first(end) + radius * std::cos(gamma);
    const double new_y = second(end) + radius * std::sin(gamma);
    const double sweep = swept_angle(opx, opy, fit.c1, fit.c2, fit.turn, first(end), second(end));
    if (beta < -kCompCornerTolerance || beta > kCompPi + kCompCornerTolerance ||
        (std::fabs(beta - kCompPi) < kCompCornerTolerance && !tool_inside_arc(side, fit.turn))) {  // concave
      if (queue_.empty() || queue_.front().kind != Queued::Kind::arc) {  // line to arc
        const double toward = arc_radius * std::sin(beta - kCompHalfPi);
        double angle = 0.0, from_centre = 0.0;
        if (tool_inside_arc(side, fit.turn)) {
          from_centre = arc_radius - radius;
          const double l = (toward + radius) / from_centre;
          if (l > 1.0 || l < -1.0) throw NgcError(column, "arc move in a concave corner cannot be reached by the tool without gouging");
          angle = fit.turn > 0 ? theta + std::asin(l) : theta - std::asin(l);
        } else {
          from_centre = arc_radius + radius;
          const double l = (toward - radius) / from_centre;
          if (l > 1.0 || l < -1.0) throw NgcError(column, "arc move in a concave corner cannot be reached by the tool without gouging");
          angle = fit.turn > 0 ? theta + kCompPi - std::asin(l) : theta + kCompPi + std::asin(l);
        }
        move_endpoint_and_flush(fit.c1 + from_centre * std::cos(angle), fit.c2 + from_centre * std::sin(angle));
      } else {  // arc to arc: where the two compensated circles meet
        const Queued& prev = queue_.front();
        const double old_radius = std::hypot(prev.c2 - second(prev.end), prev.c1 - first(prev.end));
        const double new_radius = tool_inside_arc(side, fit.turn) ? arc_radius - radius : arc_radius + radius;
        const double centres = std::hypot(prev.c2 - fit.c2, prev.c1 - fit.c1);
        if (old_radius == 0.0 || centres == 0.0)
          throw NgcError(column, "arc to arc motion is invalid because the arcs have the same centre");
        const double a = (old_radius * old_radius + centres * centres - new_radius * new_radius) / (2.0 * old_radius * centres);
        if (a > 1.0 || a < -1.0)
          throw NgcError(column, "an arc then an arc make a corner the compensated tool cannot fit in without gouging");
        const double pullback = std::acos(a);
        const double towards = std::atan2(fit.c2 - prev.c2, fit.c1 - prev.c1);
        const bool plus = tool_inside_arc(side, prev.turn) ? fit.turn > 0 : fit.turn <= 0;
        const double dir = plus ? towards + pullback : towards - pullback;
        move_endpoint_and_flush(prev.c1 + old_radius * std::cos(dir), prev.c2 + old_radius * std::sin(dir));
      }
      enqueue_arc(sweep, new_x, new_y, fit.c1, fit.c2, fit.turn, third(end));
    } else if (beta > kCompCornerTolerance) {  // convex: round the programmed corner first
      const double mid_x = opx + radius * std::cos(delta);
      const double mid_y = opy + radius * std::sin(delta);
      dequeue();
      enqueue_arc(0.0, mid_x, mid_y, opx, opy, side == kCompLeft ? -1 : 1, third(pos_));
      dequeue();
      set_endpoint(mid_x, mid_y);
      enqueue_arc(sweep, new_x, new_y, fit.c1, fit.c2, fit.turn, third(end));
    } else {  // tangent
      dequeue();
      set_endpoint(cx, cy);
      enqueue_arc(sweep, new_x, new_y, fit.c1, fit.c2, fit.turn, third(end));
    }
    programmed_ = end;
    pos_ = point(new_x, new_y, third(end));
  }
  canon_pos_ = pos_;
}

// The entry arc: the programmed arc runs from the tool's centre to the
// programmed end; the tool's arc keeps it tangent to that arc's circle there.
void CanonMachine::comp_arc_first(const NgcBlock& block, bool clockwise, const Vec3& end, int column) {
  const double cx = first(pos_), cy = second(pos_);
  const double radius = comp_radius_;
  const bool inside = (comp_side_ == kCompLeft && !clockwise) || (comp_side_ == kCompRight && clockwise);
  if (std::hypot(first(end) - cx, second(end) - cy) <= radius)
    throw NgcError(column, "the cutter radius compensation entry arc's radius is not greater than the tool radius");
  if (block.has('r') && inside && std::fabs(length(block.value('r'))) <= radius)
    throw NgcError(block.column('r'), "the tool radius is not less than the arc's radius with cutter radius compensation");
  const ArcFit fit = arc_fit(block, clockwise, cx, cy, first(end), second(end), column);
  if (!block.has('r') && inside && std::hypot(fit.c1 - cx, fit.c2 - cy) <= radius)
    throw NgcError(column, "the tool radius is not less than the arc's radius with cutter radius compensation");
  const double gamma = tool_inside_arc(comp_side_, fit.turn) ? std::atan2(fit.c2 - second(end), fit.c1 - first(end))
                                                             : std::atan2(second(end) - fit.c2, first(end) - fit.c1);
  comp_first_ = false;
  programmed_ = end;
  const double ex = first(end) + radius * std::cos(gamma);
  const double ey = second(end) + radius * std::sin(gamma);
  // The new centre: on the line from the new end towards the old centre,
  // as far as makes it equally far from the start and the new end.
  const double half_chord = std::hypot(cy - ey, cx - ex) / 2.0;
  const double to_centre = std::atan2(fit.c2 - ey, fit.c1 - ex);
  const double corner = std::atan2(cy - ey, cx - ex) - to_centre;
  if (std::fabs(std::cos(corner)) < kCompEqualTolerance)
    throw NgcError(column, "the tool radius is not less than the arc's radius with cutter radius compensation");
  const double centre_distance = half_chord / std::cos(corner);
  const double ncx = ex + centre_distance * std::cos(to_centre);
  const double ncy = ey + centre_distance * std::sin(to_centre);
  const double tolerance_mm = unit_mm_ == 1.0 ? 0.005 : 0.0005 * 25.4;
  if (std::fabs(std::hypot(ncx - ex, ncy - ey) - std::hypot(ncx - cx, ncy - cy)) > tolerance_mm)
    throw NgcError(column, "cutter radius compensation could not fit the entry arc (an interpreter bug)");
  if (comp_orientation_ != 0 && comp_orientation_ != 9) {  // a lathe tool: its origin first, or the arc is none
    enqueue_line(10, 0.0, 0.0, point(cx, cy, third(pos_)));
    set_endpoint(cx, cy);
  }
  enqueue_arc(swept_angle(cx, cy, ncx, ncy, fit.turn, ex, ey), ex, ey, ncx, ncy, fit.turn, third(end));
  pos_ = point(ex, ey, third(end));
}

}  // namespace tnv::gcode
