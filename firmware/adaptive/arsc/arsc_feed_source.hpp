#pragma once
// The S3 force loop on the board: a feed-override source for the running
// program (design notes "Motion": feed override sits between planner and
// interpolator). Every period_ticks ticks it reads the force the tick
// latched, the table's feed along the path and the programmed feed, runs
// the outer ARSC (outer_arsc.hpp: estimate, next input, gain update) and
// turns the feed it wants into a feed override of the element being run.
// The look-ahead planner then reaches that feed at its own acceleration and
// jerk limits, so no override change can break an axis limit; the force
// loop never writes a DAC.
//
// It runs inside the tick (TickTask::tick, after the snapshot and before
// the motion core's step), because the value it needs is the tick's own
// latched force and the override it sets should move this tick's path
// point: run beside the tick it would need a mailbox both ways and would
// act a tick later. The work is bounded: between samples a few
// multiplications; at a sample one scalar RLS update, one law evaluation
// and one 4 x 4 gain design (fixed-size Eigen, no allocation, under 1 us on
// the build host, docs/reproduction-s3.md "Speed").
//
// The override stays within [override_min, override_max] x the operator's
// override (never above 1.5) of the running element's programmed feed: an
// operator (or a host) turning the override down to 50 % halves the fastest
// feed the force loop may ask for, and 0 holds the path. While the program does not
// cut (feed hold, a controlled stop, a starved queue, a dwell at the front)
// the loop does not sample and holds its command; when cutting resumes it
// restarts its compensator with the soft start, keeping the cutting-gain
// estimate.
#include <array>
#include <cstdint>

#include "firmware/adaptive/arsc/arsc_source_params.hpp"
#include "firmware/adaptive/arsc/outer_arsc.hpp"

namespace tnv::fw::arsc {

enum class ArscSourceState : std::uint8_t {
  off = 0,      // arsc.enable off
  waiting = 1,  // on, no program running
  cutting = 2,  // sampling and setting the override
  paused = 3,   // the program does not cut now: command held, no samples
};

constexpr const char* to_string(ArscSourceState s) noexcept {
  switch (s) {
    case ArscSourceState::off: return "off";
    case ArscSourceState::waiting: return "waiting";
    case ArscSourceState::cutting: return "cutting";
    case ArscSourceState::paused: return "paused";
  }
  return "?";
}

// What the tick gives the source, once per tick while a program runs.
struct ArscFeedInput {
  double force_n = 0.0;                          // this tick's force (ADC x force.n_per_volt)
  std::array<double, 2> position_mm{};           // measured (encoders)
  std::array<double, 2> speed_mm_s{};            // measured (M-method)
  // F of the planned element the path runs on (MotionInterpolator::running_feed_mm_s);
  // 0 while it does not run (feed hold, stop, starved queue, a dwell): no sample then.
  double programmed_feed_mm_s = 0.0;
  double operator_override = 1.0;                // the host's / operator's override, 0 .. 1.5
};

// For telemetry and capture (TLM_ARSC, capture channels).
struct ArscSourceStatus {
  ArscSourceState state = ArscSourceState::off;
  double force_n = 0.0;                 // last sample
  double force_ref_n = 0.0;             // f* now (soft start included)
  double feed_override = 1.0;           // what the source set this tick
  double command_mm_s = 0.0;            // the loop's feed command (held between samples)
  double cutting_gain_n_per_mm_s = 0.0; // estimate
  bool clamped = false;                 // the last sample's command was at the edge of its range
  std::uint32_t samples = 0;            // since the program started
  std::uint32_t clamped_samples = 0;
  std::uint32_t refused_designs = 0;    // gain designs refused (last good gains kept)
};

class ArscFeedSource {
 public:
  ArscFeedSource() noexcept;
  // Outside the tick (construction, TickTask::apply_config). params must
  // pass validate(); otherwise the source stays as it was and says why.
  ParamCheck configure(const ArscSourceParams& params) noexcept;
  // f* on line (arsc.force_ref_n is live); false when not finite or < 0.
  bool set_force_ref_n(double force_ref_n) noexcept;

  // A program started (from holding) / ended (holding, fault, disable).
  void start(const std::array<double, 2>& position_mm) noexcept;
  void stop() noexcept;
  bool running() const noexcept { return running_; }
  bool enabled() const noexcept { return params_.enabled; }

  // One tick of a running program: the feed override to apply this tick.
  double tick(const ArscFeedInput& in) noexcept;

  const ArscSourceStatus& status() const noexcept { return status_; }
  const ArscSourceParams& params() const noexcept { return params_; }
  const OuterArsc& loop() const noexcept { return loop_; }

 private:
  void sample(const ArscFeedInput& in, double lo_ratio, double hi_ratio) noexcept;

  ArscSourceParams params_{};
  OuterArsc loop_;
  ArscSourceStatus status_{};
  bool running_ = false;
  bool was_cutting_ = false;
  std::uint32_t phase_ticks_ = 0;       // ticks since the last sample
  std::uint64_t cutting_ticks_ = 0;     // since the cut (re)started: the soft start's clock
  std::array<double, 2> last_sample_mm_{};
};

}  // namespace tnv::fw::arsc
