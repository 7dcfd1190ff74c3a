// Every parameter of the groups the tick task keeps a copy of (the
// controllers' gains and model, the observer, the planner's limits, the
// force loop) reaches that copy on the next tick when it alone changes:
// TickTask::apply_config() tells a changed group by its operator==, so a
// field added to a group's struct is compared without a hand-written list.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "firmware/can/node_settings.hpp"
#include "firmware/can/param_table.hpp"
#include "firmware/tick/tick_task.hpp"
#include "tests/firmware/fake_io_board.hpp"

namespace tnv::fw {
namespace {

struct ReachBench {
  explicit ReachBench(const FirmwareConfig& config) : task(board, config) { tick(); }
  void tick() {
    board.next_tick();
    task.tick();
  }
  test::FakeIoBoard board;
  TickTask task;
};

bool reach_in_group(const char* name, const char* group) { return std::strstr(name, group) != nullptr; }

// The groups the task copies into a controller, observer, planner or force loop.
bool reach_cached_group(const char* name) {
  for (const char* g : {".sliding.", ".pid.", ".model.", ".observer.", ".path.", "path.tolerance_mm", "arsc.",
                        ".limits.position_m"})
    if (reach_in_group(name, g)) return true;
  return false;
}

// What the task runs with equals its config (each group's operator==).
std::string reach_stale_copies(const TickTask& t) {
  std::string stale;
  const FirmwareConfig& c = t.config();
  for (const hal::Axis ax : {hal::Axis::x, hal::Axis::y}) {
    const AxisConfig& a = c.axis[hal::index(ax)];
    const std::string p = ax == hal::Axis::x ? "x " : "y ";
    if (!(t.pid_params(ax) == a.pid)) stale += p + "pid; ";
    if (!(t.sliding_params(ax) == a.sliding)) stale += p + "sliding; ";
    if (!(t.controller_model(ax) == a.model)) stale += p + "model; ";
    if (!(t.observer_params(ax) == a.observer)) stale += p + "observer; ";
  }
  if (!(t.motion().limits() == path_limits(c))) stale += "planner limits; ";
  if (!(t.feed_source().params() == c.arsc)) stale += "force loop; ";
  return stale;
}

// Values near `v` to try (the first one the config accepts is taken).
std::vector<double> reach_candidates(const can::ParamDef& p, double v) {
  if (p.type == can::ParamType::boolean) return {1.0 - v};
  std::vector<double> out;
  for (const double f : {1.01, 0.99, 1.1, 0.9}) out.push_back(v * f);
  for (const double d : {0.01, -0.01, 0.1, 1.0}) out.push_back(v + d * (p.max - p.min > 0 ? 1.0 : 0.0));
  return out;
}

TEST(TickTaskParamReach, EachCachedParameterReachesTheTaskOnTheNextTick) {
  const can::NodeSettings base = can::default_node_settings();
  int tried = 0;
  std::vector<std::string> never_accepted;
  for (const can::ParamDef& p : can::param_table()) {
    if (p.access != can::Access::read_write || !reach_cached_group(p.name)) continue;
    ReachBench b(base.firmware);
    const double v = p.get(base);
    bool accepted = false;
    for (const double candidate : reach_candidates(p, v)) {
      if (candidate < p.min || candidate > p.max || candidate == v) continue;
      can::NodeSettings changed = base;
      p.set(changed, candidate);
      if (p.get(changed) == v) continue;  // the wire's precision
      if (b.task.apply_config(changed.firmware) != CommandStatus::ok) continue;
      accepted = true;
      break;
    }
    if (!accepted) {
      never_accepted.push_back(p.name);
      continue;
    }
    ++tried;
    b.tick();
    EXPECT_EQ(reach_stale_copies(b.task), "") << p.name << " changed alone did not reach what the task runs with";
  }
  EXPECT_GT(tried, 60) << "the table's cached groups were not exercised";
  // Parameters no nearby value of which is valid alone (e.g. the observer's
  // switch with its zero default gains) are named, so the list stays short.
  EXPECT_LE(never_accepted.size(), 8u) << [&] {
    std::string s;
    for (const std::string& n : never_accepted) s += n + " ";
    return s;
  }();
}

// The comparison itself: one field of each cached group changed, the
// group's operator== sees it (a field left out of a hand-written
// comparison would not be).
TEST(TickTaskParamReach, EachGroupsComparisonSeesEachOfItsFieldsThroughTheTable) {
  const can::NodeSettings base = can::default_node_settings();
  int compared = 0;
  for (const can::ParamDef& p : can::param_table()) {
    if (p.access != can::Access::read_write) continue;
    can::NodeSettings changed = base;
    const double v = p.get(base);
    p.set(changed, p.type == can::ParamType::boolean ? 1.0 - v : v + 1.0);
    if (p.get(changed) == v) continue;
    if (std::strncmp(p.name, "x.", 2) != 0 && std::strncmp(p.name, "y.", 2) != 0 &&
        std::strncmp(p.name, "arsc.", 5) != 0)
      continue;
    if (reach_in_group(p.name, ".shaper.")) continue;  // the shaper is no part of FirmwareConfig
    ++compared;
    EXPECT_FALSE(changed.firmware == base.firmware) << p.name << ": FirmwareConfig's == misses it";
  }
  EXPECT_GT(compared, 80);
}

}  // namespace
}  // namespace tnv::fw
