#pragma once
// The operator's feed holds as a schedule (--hold-at S --resume-at S, each
// repeatable, on `tnv-hil path` and `tnvctl run`): the feed is held from
// each hold time to its resume time, seconds from the program's start, so
// a hold can be run, repeated and scored without a hand on a key.
#include <string>
#include <vector>

namespace tnv::gcode {

struct FeedHoldWindow {
  double hold_at_s = 0.0;
  double resume_at_s = 0.0;
};

// The windows from the two lists, paired in order. An empty string when they
// are good; else why not (as many holds as resumes, finite, 0 <= hold <
// resume <= the next hold), and `windows` is left empty.
std::string feed_hold_windows(const std::vector<double>& hold_at_s, const std::vector<double>& resume_at_s,
                              std::vector<FeedHoldWindow>& windows);

// True while t_s is inside a window (hold_at_s <= t_s < resume_at_s).
bool feed_held_at(const std::vector<FeedHoldWindow>& windows, double t_s) noexcept;

}  // namespace tnv::gcode
