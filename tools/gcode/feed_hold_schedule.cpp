#include "tools/gcode/feed_hold_schedule.hpp"

#include <cmath>
#include <cstdio>

namespace tnv::gcode {

namespace {

std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", s);
  return buf;
}

}  // namespace

std::string feed_hold_windows(const std::vector<double>& hold_at_s, const std::vector<double>& resume_at_s,
                              std::vector<FeedHoldWindow>& windows) {
  windows.clear();
  if (hold_at_s.size() != resume_at_s.size())
    return "--hold-at and --resume-at come in pairs: " + std::to_string(hold_at_s.size()) + " hold(s), " +
           std::to_string(resume_at_s.size()) + " resume(s)";
  std::vector<FeedHoldWindow> out;
  double previous_resume_s = 0.0;
  for (std::size_t i = 0; i < hold_at_s.size(); ++i) {
    const FeedHoldWindow w{hold_at_s[i], resume_at_s[i]};
    if (!std::isfinite(w.hold_at_s) || !std::isfinite(w.resume_at_s) || w.hold_at_s < 0.0)
      return "--hold-at / --resume-at must be finite seconds from the program's start, >= 0";
    if (!(w.resume_at_s > w.hold_at_s))
      return "--resume-at " + seconds_text(w.resume_at_s) + " must come after its --hold-at " +
             seconds_text(w.hold_at_s);
    if (i > 0 && w.hold_at_s < previous_resume_s)
      return "--hold-at " + seconds_text(w.hold_at_s) + " comes before the previous --resume-at " +
             seconds_text(previous_resume_s) + " (give the holds in time order)";
    previous_resume_s = w.resume_at_s;
    out.push_back(w);
  }
  windows = std::move(out);
  return {};
}

bool feed_held_at(const std::vector<FeedHoldWindow>& windows, double t_s) noexcept {
  for (const FeedHoldWindow& w : windows)
    if (t_s >= w.hold_at_s && t_s < w.resume_at_s) return true;
  return false;
}

}  // namespace tnv::gcode
