#include "tools/gcode/ngc_program_flow.hpp"

#include <algorithm>
#include <cmath>

#include "tools/gcode/ngc_error.hpp"

namespace tnv::gcode {

ProgramFlow::ProgramFlow(std::vector<std::pair<std::size_t, NgcOWord>> o_words, std::size_t line_count,
                         std::size_t max_lines_run)
    : line_count_(line_count), max_lines_run_(max_lines_run) {
  o_lines_.reserve(o_words.size());
  for (auto& [line, o] : o_words) o_lines_.push_back({line, std::move(o), line});
  // A label opens one block (sub, if, while, do, repeat): LinuxCNC refuses
  // a second block under the same label.
  std::map<std::string, std::size_t> opened;
  for (OLine& l : o_lines_) {
    const OKeyword k = l.o.keyword;
    const bool opens = k == OKeyword::sub || k == OKeyword::if_ || k == OKeyword::do_ || k == OKeyword::repeat ||
                       (k == OKeyword::while_ && !closes_do(l.line));
    if (!opens) continue;
    const auto [it, inserted] = opened.emplace(l.o.name, l.line);
    if (!inserted) l.first_opening = it->second;
  }
}

std::size_t ProgramFlow::o_index_from(std::size_t line) const {
  return static_cast<std::size_t>(
      std::lower_bound(o_lines_.begin(), o_lines_.end(), line, [](const OLine& l, std::size_t v) { return l.line < v; }) -
      o_lines_.begin());
}

const NgcOWord& ProgramFlow::o_at(std::size_t line) const {
  static const NgcOWord kNone{};
  const std::size_t k = o_index_from(line);
  return k < o_lines_.size() && o_lines_[k].line == line ? o_lines_[k].o : kNone;
}

std::optional<std::size_t> ProgramFlow::next_line() {
  if (pc_ >= line_count_) return std::nullopt;
  if (++lines_run_ > max_lines_run_)
    throw NgcError(1, "more than " + std::to_string(max_lines_run_) + " lines run: a loop that does not end?");
  current_ = pc_++;
  return current_;
}

std::optional<ProgramFlow::Definition> ProgramFlow::definition_holding(std::size_t line) const {
  for (std::size_t i = 0; i < o_lines_.size() && o_lines_[i].line <= line; ++i) {
    if (o_lines_[i].o.keyword != OKeyword::sub) continue;
    const std::string& name = o_lines_[i].o.name;
    std::size_t e = i + 1;
    while (e < o_lines_.size() && !(o_lines_[e].o.keyword == OKeyword::endsub && o_lines_[e].o.name == name)) ++e;
    const std::size_t end = e < o_lines_.size() ? o_lines_[e].line : line_count_;
    if (line <= end) return Definition{name, o_lines_[i].line, std::min(end, line_count_ - 1)};
    i = e;
  }
  return std::nullopt;
}

std::size_t ProgramFlow::find_forward(std::size_t from, const std::string& name,
                                      std::initializer_list<OKeyword> keywords, int column, const char* what) const {
  for (std::size_t i = o_index_from(from); i < o_lines_.size(); ++i) {
    if (o_lines_[i].o.name != name) continue;
    for (OKeyword k : keywords)
      if (o_lines_[i].o.keyword == k) return o_lines_[i].line;
  }
  throw NgcError(column, "o" + name + ": " + what + " not found");
}

std::size_t ProgramFlow::find_backward(std::size_t from, const std::string& name, OKeyword keyword, int column,
                                       const char* what) const {
  for (std::size_t i = o_index_from(from + 1); i-- > 0;)
    if (o_lines_[i].o.name == name && o_lines_[i].o.keyword == keyword) return o_lines_[i].line;
  throw NgcError(column, "o" + name + ": " + what + " not found");
}

bool ProgramFlow::closes_do(std::size_t while_line) const {
  const std::string& name = o_at(while_line).name;
  for (std::size_t i = o_index_from(while_line); i-- > 0;) {
    if (o_lines_[i].o.name != name) continue;
    const OKeyword k = o_lines_[i].o.keyword;
    if (k == OKeyword::do_) return true;
    if (k == OKeyword::while_ || k == OKeyword::endwhile || k == OKeyword::sub || k == OKeyword::endsub) return false;
  }
  return false;
}

// The line that ends the loop named `name` (endwhile, endrepeat or a do's while).
std::size_t ProgramFlow::loop_end(std::size_t from, const std::string& name, int column) const {
  for (std::size_t i = o_index_from(from); i < o_lines_.size(); ++i) {
    const OLine& l = o_lines_[i];
    if (l.o.name != name) continue;
    if (l.o.keyword == OKeyword::endwhile || l.o.keyword == OKeyword::endrepeat) return l.line;
    if (l.o.keyword == OKeyword::while_ && closes_do(l.line)) return l.line;
  }
  throw NgcError(column, "o" + name + ": the end of the loop not found");
}

void ProgramFlow::execute(const NgcOWord& o, NgcParameters& params) {
  const std::size_t at = current_;
  const auto condition = [&]() {
    if (o.args.size() != 1) throw NgcError(o.column, "o" + o.name + ": needs one [condition]");
    return o.args[0] != 0.0;
  };
  const std::size_t k_at = o_index_from(at);
  const std::size_t first_opening =
      k_at < o_lines_.size() && o_lines_[k_at].line == at ? o_lines_[k_at].first_opening : at;
  if (first_opening != at)
    throw NgcError(o.column, "duplicate O-word label o" + o.name + " (it opened a block on line " +
                                 std::to_string(first_opening + 1) + ")");
  const bool via_branch = branch_target_ == at;
  branch_target_.reset();
  switch (o.keyword) {
    case OKeyword::none: break;
    case OKeyword::sub:
      pc_ = find_forward(at + 1, o.name, {OKeyword::endsub}, o.column, "endsub") + 1;
      break;
    case OKeyword::endsub:
    case OKeyword::ret: {
      if (frames_.empty()) {
        if (o.keyword == OKeyword::ret) throw NgcError(o.column, "o" + o.name + " return outside a subroutine");
        throw NgcError(o.column, "o" + o.name + " endsub outside a subroutine");
      }
      const Frame f = frames_.back();
      frames_.pop_back();
      for (auto it = repeats_left_.begin(); it != repeats_left_.end();)
        it = it->first.first > frames_.size() ? repeats_left_.erase(it) : std::next(it);
      params.pop_scope();
      for (int k = 0; k < 30; ++k) params.set(k + 1, f.saved[static_cast<std::size_t>(k)], o.column);
      if (!o.args.empty()) {
        params.set("_value", o.args[0]);
        params.set("_value_returned", 1.0);
      } else {
        params.set("_value_returned", 0.0);
      }
      pc_ = f.return_to;
      break;
    }
    case OKeyword::call: {
      std::size_t sub = line_count_;
      for (const OLine& l : o_lines_)
        if (l.o.keyword == OKeyword::sub && l.o.name == o.name) {
          sub = l.line;
          break;
        }
      if (sub == line_count_) {
        const bool named = o.name.find_first_not_of("0123456789") != std::string::npos;
        throw NgcError(o.column, named ? "o<" + o.name + "> call: no o<" + o.name + "> sub in the program, nor a file " +
                                             o.name + ".ngc on the subroutine path"
                                       : "o" + o.name + " call: no subroutine o" + o.name + " sub in the program");
      }
      if (frames_.size() >= kMaxCallDepth) throw NgcError(o.column, "subroutine calls nested too deeply");
      if (o.args.size() > 30) throw NgcError(o.column, "more than 30 subroutine arguments");
      Frame f;
      f.return_to = at + 1;
      for (int k = 0; k < 30; ++k) f.saved[static_cast<std::size_t>(k)] = params.get(k + 1, o.column);
      frames_.push_back(f);
      params.push_scope();
      for (int k = 0; k < 30; ++k)
        params.set(k + 1, static_cast<std::size_t>(k) < o.args.size() ? o.args[static_cast<std::size_t>(k)] : 0.0,
                   o.column);
      pc_ = sub + 1;
      break;
    }
    case OKeyword::if_:
      if (!condition()) {
        pc_ = find_forward(at + 1, o.name, {OKeyword::elseif, OKeyword::else_, OKeyword::endif}, o.column, "endif");
        branch_target_ = pc_;
      }
      break;
    case OKeyword::elseif:
      if (!via_branch) {  // the branch before it ran: done with the if
        pc_ = find_forward(at + 1, o.name, {OKeyword::endif}, o.column, "endif") + 1;
      } else if (!condition()) {
        pc_ = find_forward(at + 1, o.name, {OKeyword::elseif, OKeyword::else_, OKeyword::endif}, o.column, "endif");
        branch_target_ = pc_;
      }
      break;
    case OKeyword::else_:
      if (!via_branch) pc_ = find_forward(at + 1, o.name, {OKeyword::endif}, o.column, "endif") + 1;
      break;
    case OKeyword::endif: break;
    case OKeyword::do_: break;
    case OKeyword::while_:
      if (closes_do(at)) {
        if (condition()) pc_ = find_backward(at, o.name, OKeyword::do_, o.column, "do") + 1;
      } else if (!condition()) {
        pc_ = find_forward(at + 1, o.name, {OKeyword::endwhile}, o.column, "endwhile") + 1;
      }
      break;
    case OKeyword::endwhile:
      pc_ = find_backward(at, o.name, OKeyword::while_, o.column, "while");
      break;
    case OKeyword::repeat: {
      if (o.args.size() != 1) throw NgcError(o.column, "o" + o.name + " repeat needs one [count]");
      const double n = std::floor(o.args[0]);
      const std::size_t end = find_forward(at + 1, o.name, {OKeyword::endrepeat}, o.column, "endrepeat");
      if (n <= 0.0) {
        pc_ = end + 1;
      } else {
        repeats_left_[{frames_.size(), at}] = static_cast<long>(std::fmin(n, 1e15));
      }
      break;
    }
    case OKeyword::endrepeat: {
      const std::size_t start = find_backward(at, o.name, OKeyword::repeat, o.column, "repeat");
      auto it = repeats_left_.find({frames_.size(), start});
      if (it != repeats_left_.end() && --it->second > 0) {
        pc_ = start + 1;
      } else if (it != repeats_left_.end()) {
        repeats_left_.erase(it);
      }
      break;
    }
    case OKeyword::break_: {
      const std::size_t end = loop_end(at + 1, o.name, o.column);
      if (o_at(end).keyword == OKeyword::endrepeat) {
        const std::size_t start = find_backward(end, o.name, OKeyword::repeat, o.column, "repeat");
        repeats_left_.erase({frames_.size(), start});
      }
      pc_ = end + 1;
      break;
    }
    case OKeyword::continue_: {
      const std::size_t end = loop_end(at + 1, o.name, o.column);
      pc_ = o_at(end).keyword == OKeyword::endwhile ? find_backward(end, o.name, OKeyword::while_, o.column, "while")
                                                  : end;
      break;
    }
  }
}

}  // namespace tnv::gcode
