#include "tools/gcode/gcode_program.hpp"

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>

#include "drivers/storage/regular_file.hpp"

namespace tnv::gcode {

namespace {

using fw::motion::Segment;
using fw::motion::SegmentKind;
using fw::motion::SegmentRefusal;

constexpr double kInch_mm = 25.4;

struct Word {
  char letter = 0;
  double value = 0.0;
  int column = 0;
};

struct Modal {
  int motion = -1;  // 0..3, -1 before the first motion code
  bool absolute = true;
  double unit_mm = 1.0;
  double feed_mm_s = 0.0;  // 0: no F yet
  PlanePoint position_mm{};
};

class LineError {
 public:
  LineError(int column, std::string message) : column_(column), message_(std::move(message)) {}
  int column() const { return column_; }
  const std::string& message() const { return message_; }

 private:
  int column_;
  std::string message_;
};

// Words of one line, comments removed. Throws LineError (host side only).
std::vector<Word> split_words(std::string_view line) {
  std::vector<Word> words;
  std::size_t i = 0;
  while (i < line.size()) {
    const char c = line[i];
    if (c == ' ' || c == '\t' || c == '\r') {
      ++i;
      continue;
    }
    if (c == ';') break;
    if (c == '(') {
      const std::size_t close = line.find(')', i);
      if (close == std::string_view::npos) throw LineError(static_cast<int>(i) + 1, "comment not closed");
      i = close + 1;
      continue;
    }
    if (c == '%' && words.empty()) {  // program delimiter
      ++i;
      continue;
    }
    if (!std::isalpha(static_cast<unsigned char>(c)))
      throw LineError(static_cast<int>(i) + 1, std::string("expected a word letter, found '") + c + "'");
    Word w;
    w.letter = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    w.column = static_cast<int>(i) + 1;
    ++i;
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::size_t end = i;
    if (end < line.size() && (line[end] == '+' || line[end] == '-')) ++end;
    while (end < line.size() && (std::isdigit(static_cast<unsigned char>(line[end])) || line[end] == '.')) ++end;
    std::string number(line.substr(i, end - i));
    if (!number.empty() && number[0] == '+') number.erase(0, 1);
    const auto [ptr, ec] = std::from_chars(number.data(), number.data() + number.size(), w.value);
    if (number.empty() || ec != std::errc() || ptr != number.data() + number.size() || !std::isfinite(w.value))
      throw LineError(w.column, std::string("word ") + w.letter + " needs a number");
    i = end;
    words.push_back(w);
  }
  return words;
}

std::string g_name(double value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

bool is_integer_code(double v, int code) { return std::fabs(v - code) < 1e-9; }

struct LineWords {
  std::array<const Word*, 26> by_letter{};  // X Y I J R F P N
  std::vector<const Word*> g;
  std::vector<const Word*> m;
  const Word* get(char letter) const { return by_letter[static_cast<std::size_t>(letter - 'A')]; }
};

LineWords classify(const std::vector<Word>& words) {
  LineWords lw;
  for (const Word& w : words) {
    switch (w.letter) {
      case 'G': lw.g.push_back(&w); break;
      case 'M': lw.m.push_back(&w); break;
      case 'X': case 'Y': case 'I': case 'J': case 'R': case 'F': case 'P': case 'N': {
        const Word*& slot = lw.by_letter[static_cast<std::size_t>(w.letter - 'A')];
        if (slot) throw LineError(w.column, std::string("word ") + w.letter + " twice on one line");
        slot = &w;
        break;
      }
      default:
        throw LineError(w.column, std::string("unsupported word ") + w.letter +
                                      (w.letter == 'Z' || w.letter == 'A' || w.letter == 'B' || w.letter == 'C'
                                           ? " (this table has X and Y only)"
                                           : ""));
    }
  }
  return lw;
}

void add_segment(GcodeProgram& program, Modal& modal, Segment seg, int column, const GcodeOptions& options) {
  fw::motion::SegmentGeometry g;
  const SegmentRefusal r = fw::motion::prepare(seg, modal.position_mm, options.limits, g);
  if (r != SegmentRefusal::none) throw LineError(column, std::string("segment refused: ") + fw::motion::to_string(r));
  program.segments.push_back(seg);
  program.geometry.push_back(g);
  modal.position_mm = g.end_mm;
}

// Centre of an R-form arc (RS274/NGC: R < 0 asks for the arc over 180 degrees).
PlanePoint r_form_centre(const PlanePoint& p0, const PlanePoint& p1, double r, bool clockwise, int column) {
  const double dx = p1[0] - p0[0], dy = p1[1] - p0[1];
  const double d = std::hypot(dx, dy);
  if (d < 1e-9) throw LineError(column, "R-form arc needs an end point other than its start");
  const double radius = std::fabs(r);
  double h2 = radius * radius - 0.25 * d * d;
  if (h2 < 0.0) {
    if (2.0 * radius < d * (1.0 - 1e-9) - 1e-6) throw LineError(column, "arc radius R too small for its end points");
    h2 = 0.0;
  }
  const double h = std::sqrt(h2);
  // Right of the chord for a clockwise arc under 180 degrees, left for counter-clockwise.
  double side = clockwise ? 1.0 : -1.0;
  if (r < 0.0) side = -side;
  return {0.5 * (p0[0] + p1[0]) + side * h * dy / d, 0.5 * (p0[1] + p1[1]) - side * h * dx / d};
}

void run_line(const std::vector<Word>& words, GcodeProgram& program, Modal& modal, const GcodeOptions& options,
              int line_number) {
  if (words.empty()) return;
  if (program.ended) throw LineError(words.front().column, "words after the program end (M2/M30)");
  const LineWords lw = classify(words);
  int motion_code = -1;
  const Word* motion_word = nullptr;
  bool dwell = false;
  for (const Word* g : lw.g) {
    const double v = g->value;
    int code = -1;
    for (int c : {0, 1, 2, 3, 4, 17, 20, 21, 90, 91})
      if (is_integer_code(v, c)) code = c;
    switch (code) {
      case 0: case 1: case 2: case 3:
        if (motion_word) throw LineError(g->column, "two motion codes on one line");
        motion_code = code;
        motion_word = g;
        break;
      case 4: dwell = true; break;
      case 17: break;
      case 20: modal.unit_mm = kInch_mm; break;
      case 21: modal.unit_mm = 1.0; break;
      case 90: modal.absolute = true; break;
      case 91: modal.absolute = false; break;
      default: throw LineError(g->column, "unsupported G-code G" + g_name(v));
    }
  }
  bool end = false;
  for (const Word* m : lw.m) {
    if (is_integer_code(m->value, 2) || is_integer_code(m->value, 30)) end = true;
    else throw LineError(m->column, "unsupported M-code M" + g_name(m->value));
  }
  if (const Word* f = lw.get('F')) {
    if (!(f->value > 0.0)) throw LineError(f->column, "feed F must be > 0");
    modal.feed_mm_s = f->value * modal.unit_mm / 60.0;  // units per minute
  }
  const Word* x = lw.get('X');
  const Word* y = lw.get('Y');
  const Word* i = lw.get('I');
  const Word* j = lw.get('J');
  const Word* r = lw.get('R');
  const Word* p = lw.get('P');
  const int first_column = words.front().column;
  if (dwell) {
    if (motion_word) throw LineError(motion_word->column, "G4 and a motion code on one line");
    if (!p) throw LineError(first_column, "G4 needs P (seconds)");
    if (x || y || i || j || r) throw LineError(first_column, "G4 takes no axis or arc words");
    add_segment(program, modal, fw::motion::dwell_for(p->value, static_cast<std::uint32_t>(line_number)), p->column,
                options);
  } else if (p) {
    throw LineError(p->column, "word P without G4");
  }
  if (motion_word) modal.motion = motion_code;
  const bool has_axis = x || y;
  if (has_axis || i || j || r) {
    if (modal.motion < 0) throw LineError(first_column, "axis words before any motion code (G0 G1 G2 G3)");
    const int column = motion_word ? motion_word->column : first_column;
    PlanePoint target = modal.position_mm;
    const std::array<const Word*, 2> axis = {x, y};
    for (std::size_t a = 0; a < 2; ++a) {
      if (!axis[a]) continue;
      const double v = axis[a]->value * modal.unit_mm;
      target[a] = modal.absolute ? v : modal.position_mm[a] + v;
    }
    const auto tag = static_cast<std::uint32_t>(line_number);
    if (modal.motion == 0 || modal.motion == 1) {
      if (i || j || r) throw LineError((i ? i : j ? j : r)->column, "I, J and R belong to G2/G3");
      if (!has_axis) return;
      // A move to where the table already is has nothing to do (as in LinuxCNC).
      if (std::hypot(target[0] - modal.position_mm[0], target[1] - modal.position_mm[1]) < 1e-9) {
        if (end) program.ended = true;
        return;
      }
      const double feed = modal.motion == 0 ? options.rapid_feed_mm_s : modal.feed_mm_s;
      if (feed <= 0.0) throw LineError(column, "feed move without a feed F");
      add_segment(program, modal, fw::motion::line_to(target, feed, tag), column, options);
    } else {
      const bool clockwise = modal.motion == 2;
      if (modal.feed_mm_s <= 0.0) throw LineError(column, "feed move without a feed F");
      PlanePoint centre{};
      if (r) {
        if (i || j) throw LineError(r->column, "R with I/J: give one arc form");
        centre = r_form_centre(modal.position_mm, target, r->value * modal.unit_mm, clockwise, r->column);
      } else {
        if (!i && !j) throw LineError(column, "arc needs I/J or R");
        // I and J are offsets from the start point (incremental arc centre).
        centre = {modal.position_mm[0] + (i ? i->value * modal.unit_mm : 0.0),
                  modal.position_mm[1] + (j ? j->value * modal.unit_mm : 0.0)};
      }
      add_segment(program, modal, fw::motion::arc_to(clockwise, target, centre, modal.feed_mm_s, tag), column,
                  options);
    }
  }
  if (end) program.ended = true;
}

}  // namespace

double GcodeProgram::programmed_length_mm() const noexcept {
  double sum = 0.0;
  for (const auto& g : geometry) sum += g.length_mm;
  return sum;
}

double GcodeProgram::programmed_time_s() const noexcept {
  double sum = 0.0;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    if (segments[k].kind == SegmentKind::dwell) sum += segments[k].dwell_s;
    else sum += geometry[k].length_mm / segments[k].feed_mm_s;
  }
  return sum;
}

GcodeResult parse_gcode(std::string_view text, const GcodeOptions& options) {
  GcodeResult result;
  Modal modal;
  modal.position_mm = options.start_mm;
  int line_number = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    ++line_number;
    try {
      run_line(split_words(text.substr(pos, eol - pos)), result.program, modal, options, line_number);
    } catch (const LineError& e) {
      result.program = {};
      result.error = GcodeError{line_number, e.column(), e.message()};
      return result;
    }
    pos = eol + 1;
  }
  return result;
}

bool read_program_file(const std::string& path, std::string& text, std::string& error) {
  return drivers::read_regular_file(path, kMaxProgramBytes, drivers::LinkPolicy::follow, text, error);
}

GcodeResult parse_gcode_file(const std::string& path, const GcodeOptions& options) {
  std::string text;
  std::string error;
  if (!read_program_file(path, text, error)) {
    GcodeResult r;
    r.error = GcodeError{0, 0, error};
    return r;
  }
  return parse_gcode(text, options);
}

std::string to_string(const GcodeError& error) {
  return (error.file.empty() ? "" : error.file + ", ") + "line " + std::to_string(error.line) + ", column " +
         std::to_string(error.column) + ": " + error.message;
}

}  // namespace tnv::gcode
