#include "firmware/can/param_table.hpp"

#include <cmath>
#include <cstring>
#include <type_traits>

#include "firmware/can/capture_channels.hpp"
#include "firmware/can/firmware_identity.hpp"
#include "firmware/can/frame_codec.hpp"
#include "firmware/can/param_rows_bore.hpp"
#include "firmware/spindle/spindle_params.hpp"
#include "firmware/compensation/excitation.hpp"
#include "firmware/control/axis_model.hpp"
#include "firmware/control/same_bytes.hpp"
#include "firmware/motion/motion_interpolator.hpp"
#include "firmware/shaper/impulse_design.hpp"

namespace tnv::fw::can {
namespace {

// Accessor pairs for one settings member. REAL: a double; INT: an integer,
// bool or enum member (the value is integral by check_value()).
#define TNV_MEMBER(path) [](const NodeSettings& s) noexcept -> const void* { return &s.path; }
#define TNV_REAL(path)                                                          \
  [](const NodeSettings& s) noexcept -> double { return s.path; },             \
      [](NodeSettings& s, double v) noexcept { s.path = v; }, nullptr, TNV_MEMBER(path)
#define TNV_INT(path)                                                                                  \
  [](const NodeSettings& s) noexcept -> double { return static_cast<double>(static_cast<long long>(s.path)); }, \
      [](NodeSettings& s, double v) noexcept {                                                          \
        s.path = static_cast<std::remove_cvref_t<decltype(s.path)>>(static_cast<long long>(v));         \
      },                                                                                               \
      nullptr, TNV_MEMBER(path)
#define TNV_RO(expr) \
  [](const NodeSettings&) noexcept -> double { return static_cast<double>(expr); }, nullptr, nullptr, nullptr
// A double member shown in another unit: the parameter is member * scale (um for a member in mm: 1000).
// Read back at f32 precision (the parameter's wire type): a value set reads
// back exactly, not with the last bit of (v / scale) * scale's rounding.
#define TNV_SCALED(path, scale)                                                                        \
  [](const NodeSettings& s) noexcept -> double { return static_cast<double>(static_cast<float>(s.path * (scale))); }, \
      [](NodeSettings& s, double v) noexcept { s.path = v / (scale); }, nullptr, TNV_MEMBER(path)

std::size_t param_count() noexcept;

constexpr const char* kOnOff = "0=off 1=on";
constexpr const char* kControllers = "0=pid 1=dvsc 2=rdvsc";
constexpr const char* kShaperTypes = "0=zv 1=zvd 2=zvdd 3=ei 4=mzv";
constexpr double kBig = 1e9;

constexpr Guard kOpen = Guard::open;
constexpr Guard kSafety = Guard::commissioning;

// Ranges of the safety parameters: what a TNV-40-class table (ball screws
// of 5..20 mm lead, under 1 m of travel, servopacks up to a few thousand
// rpm) can use. Wider values only let a fault run further before it trips
// (a following-error floor of 100 mm let a runaway run 117 mm).
// Soft travel limits: no table of this class travels 1 m.
constexpr double kTravelLimitMm = 1000.0;
// Measured-speed limit: 1000 mm/s is 3000 rpm on a 20 mm lead, the fastest
// drive of the class; below 1 mm/s the limit trips on encoder noise.
constexpr double kSpeedLimitMinMmS = 1.0;
constexpr double kSpeedLimitMaxMmS = 1000.0;
// Following-error floor: 1 um (2.4 counts) keeps quantisation from
// tripping it; 2 mm covers a first commissioning with rough gains (the
// tuned default is 0.05 mm).
constexpr double kFollowingFloorMinMm = 0.001;
constexpr double kFollowingFloorMaxMm = 2.0;
// Following-error lag: a position loop of 4 1/s lags 0.25 s; a slower
// loop cannot track a contour, so more lag only hides a runaway.
constexpr double kFollowingLagMaxS = 0.25;
// Stall level: above 0.5 mm/s (below any breakaway worth detecting; the
// reference plant's is 3 mm/s) and at most 100 mm/s, beyond which a
// stalled axis is driven near full scale before it counts.
constexpr double kStallCommandMinMmS = 0.5;
constexpr double kStallCommandMaxMmS = 100.0;
// Stall time: 100 ticks (100 ms) of drive without a count is already a
// long runaway with a lost encoder.
constexpr double kStallTicksMax = 100;
// Missed ticks: every missed tick is 1 ms of stale output; 10 in a row
// is the most a loop can ride through.
constexpr double kMissedTicksMax = 10;
// Host timeout: 0 = off (the default); a stop later than 5 s after the
// host went silent supervises nothing.
constexpr double kHostTimeoutMaxMs = 5000;
// Jog dead man: one tick at least; a jog that runs on for over 1 s after
// its operator went silent defeats the dead man.
constexpr double kJogDeadmanMinS = 0.001;
constexpr double kJogDeadmanMaxS = 1.0;
// Encoder count: 1 nm (the finest linear scales) to 10 um (1000 lines x4
// on a 40 mm lead); the TNV-40's is 0.417 um.
constexpr double kCountMinMm = 1e-6;
constexpr double kCountMaxMm = 0.01;
// DAC full scale: 10 mm/s .. 2000 mm/s (6000 rpm on a 20 mm lead); the
// TNV-40's is 166.7 mm/s. A wrong scale mis-sizes every command.
constexpr double kDacFullScaleMinMmS = 10.0;
constexpr double kDacFullScaleMaxMmS = 2000.0;

// Planner limits for programs: below 0.1 mm/s and 1 mm/s^2 a program
// crawls; 10^5 mm/s^2 (10 g) and 10^8 mm/s^3 are beyond any ball-screw
// table. validate() adds the jerk filter's bound (jerk >= accel / 64 ms).
constexpr double kPathSpeedMinMmS = 0.1;
constexpr double kPathAccelMinMmS2 = 1.0;
constexpr double kPathAccelMaxMmS2 = 1e5;
constexpr double kPathJerkMinMmS3 = 10.0;
constexpr double kPathJerkMaxMmS3 = 1e8;
// Path tolerance: 0.1 um is below an encoder count; 1 mm rounds a corner
// further than any finishing pass would accept.
constexpr double kPathToleranceMinMm = 1e-4;
constexpr double kPathToleranceMaxMm = 1.0;
// Force loop: a reference beyond 10 kN is no milling force on a table of
// this class; poles beyond 10^4 rad/s are faster than the 1 ms tick can place.
constexpr double kArscForceMaxN = 1e4;
constexpr double kArscPoleMaxRadS = 1e4;

// Homing: a search below 0.1 mm/s crawls over the travel; above 100 mm/s
// the axis overruns the switch by more than its braking distance allows.
// The latch speed sets how far the switch's release jitters (one tick at
// 10 mm/s is 10 um); below 0.01 mm/s a screw turn takes over 15 min.
constexpr double kHomeSearchMinMmS = 0.1;
constexpr double kHomeSearchMaxMmS = 100.0;
constexpr double kHomeLatchMinMmS = 0.01;
constexpr double kHomeLatchMaxMmS = 10.0;
// Travel bounds: at least 0.1 mm; back-off and index search at most 100 mm
// (five turns of a 20 mm lead: an index is at most one turn away).
constexpr double kHomeTravelMinMm = 0.1;
constexpr double kHomeLatchTravelMaxMm = 100.0;
constexpr const char* kHomeSides = "0=negative 1=positive";

bool allowed_bitrate(double kbit) noexcept { return kbit == 125 || kbit == 250 || kbit == 500 || kbit == 1000; }

// One point of an axis' per-turn lead-error table (screw_compensation.hpp).
#define TNV_TURN_ERROR_ROW(ax, base, p, j)                                                                    \
  {base + 0xD0 + (j), p "screw.turn_error_um." #j, ParamType::f32, "um", -100, 100, "", Access::read_write,      \
   Apply::idle, kOpen, TNV_SCALED(firmware.axis[ax].screw.turn_error_mm[j], 1000.0),                           \
   "per-turn lead-error table: the table's error at point " #j " of 16 over one period, measured (tnv-hil screw-fit)"}

// One axis' parameters: ax is the axis index, base its id block, p its name prefix.
#define TNV_AXIS_PARAMS(ax, base, p)                                                                                     \
  {base + 0x00, p "controller", ParamType::enumeration, "", 0, 2, kControllers,                                          \
       Access::read_write, Apply::idle, kOpen,                                                                           \
   TNV_INT(firmware.axis[ax].controller), "active loop: PID baseline, DVSC+DDC or R-DVSC+DDC"},                          \
      {base + 0x10, p "sliding.G_position_1_s", ParamType::f32, "1/s", 0, 1e5, "",                                       \
       Access::read_write, Apply::live, kOpen,                                                                           \
       TNV_REAL(firmware.axis[ax].sliding.G_position_1_s), "G = [G_position, G_speed] (S1 eq. 5)"},                      \
      {base + 0x11, p "sliding.G_speed", ParamType::f32, "", 0, 1e3, "", Access::read_write, Apply::live, kOpen,         \
       TNV_REAL(firmware.axis[ax].sliding.G_speed), "speed weight of the surface (S1 eq. 5)"},                           \
      {base + 0x12, p "sliding.eta_mm_s", ParamType::f32, "mm/s", 0, 1e4, "", Access::read_write, Apply::live, kOpen,    \
       TNV_REAL(firmware.axis[ax].sliding.eta_mm_s), "reaching-law gain eta (S1 eq. 4)"},                                \
      {base + 0x13, p "sliding.phi_mm_s", ParamType::f32, "mm/s", 0, 1e4, "", Access::read_write, Apply::live, kOpen,    \
       TNV_REAL(firmware.axis[ax].sliding.phi_mm_s), "boundary layer phi (S1 eq. 4); > eta / (q + 1)"},                  \
      {base + 0x14, p "sliding.q", ParamType::f32, "", 0, 1, "", Access::read_write, Apply::live, kOpen,                 \
       TNV_REAL(firmware.axis[ax].sliding.q), "reaching-law pole q (S1 eq. 4), 0 < q < 1"},                              \
      {base + 0x15, p "sliding.g", ParamType::f32, "", 0, 1, "", Access::read_write, Apply::live, kOpen,                 \
       TNV_REAL(firmware.axis[ax].sliding.g), "DDC gain g (S1 eq. 7), 0 < g < 1"},                                       \
      {base + 0x16, p "sliding.gamma", ParamType::f32, "", 0, 1, "", Access::read_write, Apply::live, kOpen,             \
       TNV_REAL(firmware.axis[ax].sliding.gamma), "recursive-surface weight gamma (S1 eq. 5); < min(1 - g, q)"},         \
      {base + 0x17, p "sliding.u_max_mm_s", ParamType::f32, "mm/s", 0, 1e4, "",                                          \
       Access::read_write, Apply::live, kOpen,                                                                           \
       TNV_REAL(firmware.axis[ax].sliding.u_max_mm_s), "command clamp of DVSC/R-DVSC"},                                  \
      {base + 0x20, p "pid.kp", ParamType::f32, "1/s", 0, 1e6, "", Access::read_write, Apply::live, kOpen,               \
       TNV_REAL(firmware.axis[ax].pid.kp), "proportional gain"},                                                         \
      {base + 0x21, p "pid.ki", ParamType::f32, "1/s^2", 0, 1e8, "", Access::read_write, Apply::live, kOpen,             \
       TNV_REAL(firmware.axis[ax].pid.ki), "integral gain"},                                                             \
      {base + 0x22, p "pid.kd", ParamType::f32, "", 0, 1e3, "", Access::read_write, Apply::live, kOpen,                  \
       TNV_REAL(firmware.axis[ax].pid.kd), "derivative gain"},                                                           \
      {base + 0x23, p "pid.derivative_filter_tf_s", ParamType::f32, "s", 0, 1, "",                                       \
       Access::read_write, Apply::idle, kOpen,                                                                           \
       TNV_REAL(firmware.axis[ax].pid.derivative_filter_tf_s), "derivative filter time constant; 0 = off"},              \
      {base + 0x24, p "pid.u_max_mm_s", ParamType::f32, "mm/s", 0, 1e4, "", Access::read_write, Apply::live, kOpen,      \
       TNV_REAL(firmware.axis[ax].pid.u_max_mm_s), "command clamp of the PID"},                                          \
      {base + 0x25, p "pid.feedforward", ParamType::boolean, "", 0, 1, kOnOff, Access::read_write, Apply::idle, kOpen,   \
       TNV_INT(firmware.axis[ax].pid.feedforward), "model velocity + acceleration feed-forward"},                        \
      {base + 0x30, p "model.a11", ParamType::f32, "", -1e3, 1e3, "", Access::read_write, Apply::idle, kOpen,            \
       TNV_REAL(firmware.axis[ax].model.A(0, 0)), "discrete model A(1,1) (S1 eq. 31)"},                                  \
      {base + 0x31, p "model.a12", ParamType::f32, "s", -1e3, 1e3, "", Access::read_write, Apply::idle, kOpen,           \
       TNV_REAL(firmware.axis[ax].model.A(0, 1)), "discrete model A(1,2)"},                                              \
      {base + 0x32, p "model.a21", ParamType::f32, "1/s", -1e3, 1e3, "", Access::read_write, Apply::idle, kOpen,         \
       TNV_REAL(firmware.axis[ax].model.A(1, 0)), "discrete model A(2,1)"},                                              \
      {base + 0x33, p "model.a22", ParamType::f32, "", -1e3, 1e3, "", Access::read_write, Apply::idle, kOpen,            \
       TNV_REAL(firmware.axis[ax].model.A(1, 1)), "discrete model A(2,2)"},                                              \
      {base + 0x34, p "model.b1", ParamType::f32, "s", -1e3, 1e3, "", Access::read_write, Apply::idle, kOpen,            \
       TNV_REAL(firmware.axis[ax].model.B(0)), "discrete model B(1) (position per command)"},                            \
      {base + 0x35, p "model.b2", ParamType::f32, "", -1e3, 1e3, "", Access::read_write, Apply::idle, kOpen,             \
       TNV_REAL(firmware.axis[ax].model.B(1)), "discrete model B(2) (speed per command)"},                               \
      {base + 0x40, p "shaper.type", ParamType::enumeration, "", 0, 4, kShaperTypes,                                     \
       Access::read_write, Apply::live, kOpen,                                                                           \
       TNV_INT(shaper[ax].spec.type), "input-shaper family (applied at the next quiet reference)"},                      \
      {base + 0x41, p "shaper.freq_hz", ParamType::f32, "Hz", kShaperMinFreqHz, kShaperMaxFreqHz, "",                    \
       Access::read_write, Apply::live, kOpen, TNV_REAL(shaper[ax].spec.mode.freq_hz), "mode frequency to cancel"},      \
      {base + 0x42, p "shaper.zeta", ParamType::f32, "", 0, kShaperMaxZeta, "",                                          \
       Access::read_write, Apply::live, kOpen,                                                                           \
       TNV_REAL(shaper[ax].spec.mode.zeta), "mode damping ratio"},                                                       \
      {base + 0x43, p "shaper.enable", ParamType::boolean, "", 0, 1, kOnOff, Access::read_write, Apply::live, kOpen,     \
       TNV_INT(shaper[ax].enabled), "input shaper on (takes effect at the next quiet reference)"},                       \
      {base + 0x50, p "limits.position_min_mm", ParamType::f32, "mm", -kTravelLimitMm, kTravelLimitMm, "",               \
       Access::read_write, Apply::idle, kSafety,                                                                         \
       TNV_REAL(firmware.supervisor.axis[ax].position_min_mm), "soft travel limit, low"},                                \
      {base + 0x51, p "limits.position_max_mm", ParamType::f32, "mm", -kTravelLimitMm, kTravelLimitMm, "",               \
       Access::read_write, Apply::idle, kSafety,                                                                         \
       TNV_REAL(firmware.supervisor.axis[ax].position_max_mm), "soft travel limit, high"},                               \
      {base + 0x52, p "limits.speed_max_mm_s", ParamType::f32, "mm/s", kSpeedLimitMinMmS, kSpeedLimitMaxMmS, "",         \
       Access::read_write, Apply::idle, kSafety,                                                                         \
       TNV_REAL(firmware.supervisor.axis[ax].speed_max_mm_s), "measured-speed limit"},                                   \
      {base + 0x53, p "limits.following_floor_mm", ParamType::f32, "mm", kFollowingFloorMinMm, kFollowingFloorMaxMm, "", \
       Access::read_write, Apply::idle, kSafety,                                                                         \
       TNV_REAL(firmware.supervisor.axis[ax].following.floor_mm), "following-error limit at rest"},                      \
      {base + 0x54, p "limits.following_lag_s", ParamType::f32, "s", 0, kFollowingLagMaxS, "",                           \
       Access::read_write, Apply::idle, kSafety,                                                                         \
       TNV_REAL(firmware.supervisor.axis[ax].following.lag_s), "following-error limit growth per mm/s"},                 \
      {base + 0x55, p "limits.stall_command_mm_s", ParamType::f32, "mm/s", kStallCommandMinMmS, kStallCommandMaxMmS, "", \
       Access::read_write, Apply::idle, kSafety,                                                                         \
       TNV_REAL(firmware.supervisor.axis[ax].stall.command_mm_s),                                                        \
       "stall monitor: |command| that must move the encoder (above the breakaway)"},                                     \
      {base + 0x56, p "limits.stall_ticks", ParamType::u32, "tick", 1, kStallTicksMax, "",                               \
       Access::read_write, Apply::idle, kSafety,                                                                         \
       TNV_INT(firmware.supervisor.axis[ax].stall.ticks), "stall monitor: ticks without a count that trip"},             \
      {base + 0x60, p "jog.speed_max_mm_s", ParamType::f32, "mm/s", 0, 1e4, "",                                          \
       Access::read_write, Apply::idle, kOpen,                                                                           \
       TNV_REAL(firmware.axis[ax].jog.speed_max_mm_s), "jog speed limit"},                                               \
      {base + 0x61, p "jog.accel_mm_s2", ParamType::f32, "mm/s^2", 0, 1e6, "", Access::read_write, Apply::idle, kOpen,   \
       TNV_REAL(firmware.axis[ax].jog.accel_mm_s2), "jog acceleration"},                                                 \
      {base + 0x62, p "jog.deadman_s", ParamType::f32, "s", kJogDeadmanMinS, kJogDeadmanMaxS, "",                        \
       Access::read_write, Apply::idle, kSafety,                                                                         \
       TNV_REAL(firmware.axis[ax].jog.deadman_s), "longest silence of the jog stream before the axis stops"},            \
      {base + 0x70, p "hw.count_mm", ParamType::f32, "mm", kCountMinMm, kCountMaxMm, "",                                 \
       Access::read_write, Apply::idle, kSafety,                                                                         \
       TNV_REAL(firmware.axis[ax].count_mm), "encoder count (lead / counts per rev, x4)"},                               \
      {base + 0x71, p "hw.dac_full_scale_mm_s", ParamType::f32, "mm/s", kDacFullScaleMinMmS, kDacFullScaleMaxMmS, "",    \
       Access::read_write, Apply::idle, kSafety,                                                                         \
       TNV_REAL(firmware.axis[ax].dac.full_scale_mm_s), "speed at DAC full scale (+10 V)"},                              \
      {base + 0x80, p "friction.enable", ParamType::boolean, "", 0, 1, kOnOff, Access::read_write, Apply::idle, kOpen,   \
       TNV_INT(firmware.axis[ax].friction.enabled), "friction feed-forward on (docs/autotune.md)"},                      \
      {base + 0x81, p "friction.coulomb_mm_s", ParamType::f32, "mm/s", 0, 1e3, "",                                       \
       Access::read_write, Apply::idle, kOpen,                                                                           \
       TNV_REAL(firmware.axis[ax].friction.coulomb_mm_s), "Coulomb friction f_c (table-speed equivalent)"},              \
      {base + 0x82, p "friction.stiction_mm_s", ParamType::f32, "mm/s", 0, 1e3, "", Access::read_write,                  \
       Apply::idle, kOpen, TNV_REAL(firmware.axis[ax].friction.stiction_mm_s), "stiction f_s >= f_c"},                   \
      {base + 0x83, p "friction.stribeck_mm_s", ParamType::f32, "mm/s", 1e-6, 1e3, "", Access::read_write,               \
       Apply::idle, kOpen, TNV_REAL(firmware.axis[ax].friction.stribeck_mm_s), "Stribeck speed v_s"},                    \
      {base + 0x84, p "friction.gain", ParamType::f32, "", 1e-6, 1e3, "", Access::read_write, Apply::idle, kOpen,        \
       TNV_REAL(firmware.axis[ax].friction.gain), "speed-loop gain K the feed-forward divides by"},                      \
      {base + 0x85, p "friction.fraction", ParamType::f32, "", 0, 1.5, "", Access::read_write, Apply::idle, kOpen,       \
       TNV_REAL(firmware.axis[ax].friction.fraction), "share of the friction model fed forward"},                        \
      {base + 0x90, p "observer.enable", ParamType::boolean, "", 0, 1, kOnOff, Access::read_write, Apply::idle, kOpen,   \
       TNV_INT(firmware.axis[ax].observer.enabled), "speed observer fed back instead of the M-method speed"},            \
      {base + 0x91, p "observer.use_position", ParamType::boolean, "", 0, 1, kOnOff, Access::read_write,                 \
       Apply::idle, kOpen, TNV_INT(firmware.axis[ax].observer.use_position), "also feed back the estimated position"},   \
      {base + 0x92, p "observer.gain_position", ParamType::f32, "", -1e3, 1e3, "",                                       \
       Access::read_write, Apply::idle, kOpen,                                                                           \
       TNV_REAL(firmware.axis[ax].observer.gain_position), "observer gain l_p (Kalman, speed_observer.hpp)"},            \
      {base + 0x93, p "observer.gain_speed_1_s", ParamType::f32, "1/s", -1e6, 1e6, "", Access::read_write,               \
       Apply::idle, kOpen, TNV_REAL(firmware.axis[ax].observer.gain_speed_1_s), "observer gain l_v"},                    \
      {base + 0x94, p "observer.gain_disturbance_1_s", ParamType::f32, "1/s", -1e6, 1e6, "", Access::read_write,         \
       Apply::idle, kOpen, TNV_REAL(firmware.axis[ax].observer.gain_disturbance_1_s), "observer gain l_d"},              \
      {base + 0x95, p "observer.friction_mm_s", ParamType::f32, "mm/s", 0, 1e3, "",                                      \
       Access::read_write, Apply::idle, kOpen,                                                                           \
       TNV_REAL(firmware.axis[ax].observer.friction_mm_s), "Coulomb friction f_c / K the observer's model takes out"},   \
      {base + 0x96, p "observer.friction_deadband_mm_s", ParamType::f32, "mm/s", 1e-6, 1e3, "", Access::read_write,     \
       Apply::idle, kOpen, TNV_REAL(firmware.axis[ax].observer.friction_deadband_mm_s),                                  \
       "|estimated speed| below which the observer assumes no friction"},                                                \
      {base + 0xA0, p "path.speed_mm_s", ParamType::f32, "mm/s", kPathSpeedMinMmS, kSpeedLimitMaxMmS, "",                \
       Access::read_write, Apply::idle, kOpen, TNV_REAL(firmware.axis[ax].path.speed_mm_s),                              \
       "programs: the planner's speed limit of this axis (docs/motion.md)"},                                             \
      {base + 0xA1, p "path.accel_mm_s2", ParamType::f32, "mm/s^2", kPathAccelMinMmS2, kPathAccelMaxMmS2, "",            \
       Access::read_write, Apply::idle, kOpen, TNV_REAL(firmware.axis[ax].path.accel_mm_s2),                             \
       "programs: the planner's acceleration limit of this axis (both axes plan with the smaller)"},                     \
  {                                                                                                                      \
    base + 0xA2, p "path.jerk_mm_s3", ParamType::f32, "mm/s^3", kPathJerkMinMmS3, kPathJerkMaxMmS3, "",                  \
        Access::read_write, Apply::idle, kOpen, TNV_REAL(firmware.axis[ax].path.jerk_mm_s3),                             \
        "programs: the planner's jerk limit of this axis (at least accel / 64 ms: the jerk filter's 128 taps)"           \
  },                                                                                                                     \
    {base + 0xB0, p "homing.search_positive", ParamType::boolean, "", 0, 1, kHomeSides, Access::read_write,               \
     Apply::idle, kOpen, TNV_INT(firmware.axis[ax].homing.search_positive),                                            \
     "which end of the travel the home switch is at: the search runs toward it"},                                        \
    {base + 0xB1, p "homing.search_mm_s", ParamType::f32, "mm/s", kHomeSearchMinMmS, kHomeSearchMaxMmS, "",               \
     Access::read_write, Apply::idle, kOpen, TNV_REAL(firmware.axis[ax].homing.search_mm_s),                             \
     "homing: speed toward the switch"},                                                                                 \
    {base + 0xB2, p "homing.latch_mm_s", ParamType::f32, "mm/s", kHomeLatchMinMmS, kHomeLatchMaxMmS, "",                  \
     Access::read_write, Apply::idle, kOpen, TNV_REAL(firmware.axis[ax].homing.latch_mm_s),                              \
     "homing: speed off the switch and on to the index (<= search speed)"},                                              \
    {base + 0xB3, p "homing.position_mm", ParamType::f32, "mm", -kTravelLimitMm, kTravelLimitMm, "", Access::read_write,  \
     Apply::idle, kOpen, TNV_REAL(firmware.axis[ax].homing.position_mm),                                               \
     "position given to the index mark found after the switch: home (the soft limits are relative to it)"},             \
    {base + 0xB4, p "homing.search_max_mm", ParamType::f32, "mm", kHomeTravelMinMm, kTravelLimitMm, "",                  \
     Access::read_write, Apply::idle, kOpen, TNV_REAL(firmware.axis[ax].homing.search_max_mm),                         \
     "homing: longest search without the switch before it fails (the axis' travel)"},                                    \
  {                                                                                                                      \
    base + 0xB5, p "homing.latch_max_mm", ParamType::f32, "mm", kHomeTravelMinMm, kHomeLatchTravelMaxMm, "",              \
        Access::read_write, Apply::idle, kOpen, TNV_REAL(firmware.axis[ax].homing.latch_max_mm),                       \
        "homing: longest back-off, and longest run from the switch's release to an index edge (over one screw turn)"     \
  },                                                                                                                     \
      {base + 0xC0, p "screw.backlash_um", ParamType::f32, "um", 0, 200, "", Access::read_write, Apply::idle, kOpen,      \
       TNV_SCALED(firmware.axis[ax].screw.backlash_mm, 1000.0),                                                          \
       "backlash compensation: lost motion at a reversal, added half each way (docs/robustness.md); 0 = off"},          \
      {base + 0xC1, p "screw.backlash_rate_mm_s", ParamType::f32, "mm/s", 0.01, 100, "", Access::read_write,             \
       Apply::idle, kOpen, TNV_REAL(firmware.axis[ax].screw.backlash_rate_mm_s),                                         \
       "how fast the backlash offset changes at a reversal"},                                                            \
      {base + 0xC2, p "screw.lead_um_per_m", ParamType::f32, "um/m", -1000, 1000, "", Access::read_write, Apply::idle,   \
       kOpen, TNV_REAL(firmware.axis[ax].screw.lead_um_per_m),                                                           \
       "lead-error compensation: table travel error per metre of motor travel from the origin; 0 = off"}, \
      {base + 0xC3, p "screw.turn_period_mm", ParamType::f32, "mm", 0.1, 1000, "", Access::read_write, Apply::idle,      \
       kOpen, TNV_REAL(firmware.axis[ax].screw.turn_period_mm),                                                          \
       "per-turn lead-error table: its period (the screw's lead)"},                                                      \
      TNV_TURN_ERROR_ROW(ax, base, p, 0),                                                               \
      TNV_TURN_ERROR_ROW(ax, base, p, 1),                                                               \
      TNV_TURN_ERROR_ROW(ax, base, p, 2),                                                               \
      TNV_TURN_ERROR_ROW(ax, base, p, 3),                                                               \
      TNV_TURN_ERROR_ROW(ax, base, p, 4),                                                               \
      TNV_TURN_ERROR_ROW(ax, base, p, 5),                                                               \
      TNV_TURN_ERROR_ROW(ax, base, p, 6),                                                               \
      TNV_TURN_ERROR_ROW(ax, base, p, 7),                                                               \
      TNV_TURN_ERROR_ROW(ax, base, p, 8),                                                               \
      TNV_TURN_ERROR_ROW(ax, base, p, 9),                                                               \
      TNV_TURN_ERROR_ROW(ax, base, p, 10),                                                              \
      TNV_TURN_ERROR_ROW(ax, base, p, 11),                                                              \
      TNV_TURN_ERROR_ROW(ax, base, p, 12),                                                              \
      TNV_TURN_ERROR_ROW(ax, base, p, 13),                                                              \
      TNV_TURN_ERROR_ROW(ax, base, p, 14),                                                              \
      TNV_TURN_ERROR_ROW(ax, base, p, 15)

constexpr ParamDef kParams[] = {
    {0x0000, "sys.protocol_version", ParamType::u32, "", 0, kBig, "", Access::read_only, Apply::live, kOpen,
     TNV_RO(kProtocolVersion), "protocol version; the host refuses a node with another"},
    {0x0001, "sys.param_count", ParamType::u32, "", 0, kBig, "", Access::read_only, Apply::live, kOpen,
     TNV_RO(param_count()), "number of parameters"},
    {0x0002, "sys.capture_capacity_words", ParamType::u32, "", 0, kBig, "", Access::read_only, Apply::live, kOpen,
     TNV_RO(kCaptureCapacityWords), "capture buffer, 32-bit words"},
    {0x0003, "sys.firmware_version", ParamType::u32, "", 0, kBig, "", Access::read_only, Apply::live, kOpen,
     TNV_RO(firmware_version()), "firmware version: major * 10000 + minor * 100 + patch"},
    {0x0004, "sys.build_id", ParamType::u32, "", 0, 4294967295.0, "", Access::read_only, Apply::live, kOpen,
     TNV_RO(firmware_build_id()), "first 32 bits of the git commit the firmware was built from; 0 = unknown"},
    {0x0010, "can.node_id", ParamType::u32, "", 1, kMaxNodeId, "", Access::read_write, Apply::restart, kOpen,
     TNV_INT(can.node_id), "this node's id (identifier bits 5..0)"},
    {0x0011, "can.bitrate_kbit", ParamType::u32, "kbit/s", 125, 1000, "", Access::read_write, Apply::restart, kOpen,
     [](const NodeSettings& s) noexcept -> double { return s.can.bitrate_kbit; },
     [](NodeSettings& s, double v) noexcept { s.can.bitrate_kbit = static_cast<std::uint32_t>(v); },
     allowed_bitrate, TNV_MEMBER(can.bitrate_kbit), "bus bit rate: 125, 250, 500 or 1000"},
    {0x0012, "can.host_timeout_ms", ParamType::u32, "ms", 0, kHostTimeoutMaxMs, "", Access::read_write, Apply::live,
     kSafety,
     TNV_INT(can.host_timeout_ms), "controlled stop when no frame came from the host this long while moving; 0 = off"},
    {0x0020, "tlm.heartbeat_ms", ParamType::u32, "ms", 0, 60000, "", Access::read_write, Apply::live, kOpen,
     TNV_INT(telemetry.heartbeat_ms), "HEARTBEAT period; 0 = off"},
    {0x0021, "tlm.position_ms", ParamType::u32, "ms", 0, 60000, "", Access::read_write, Apply::live, kOpen,
     TNV_INT(telemetry.position_ms),
     "TLM_POSITION_<AXIS> period (position and following error); 0 = off. 0x0022 was tlm.following_ms (protocol 4)"},
    {0x0023, "tlm.sliding_ms", ParamType::u32, "ms", 0, 60000, "", Access::read_write, Apply::live, kOpen,
     TNV_INT(telemetry.sliding_ms), "TLM_SLIDING_X/Y period; 0 = off"},
    {0x0024, "tlm.output_ms", ParamType::u32, "ms", 0, 60000, "", Access::read_write, Apply::live, kOpen,
     TNV_INT(telemetry.output_ms), "TLM_OUTPUT period; 0 = off"},
    {0x0025, "tlm.contour_ms", ParamType::u32, "ms", 0, 60000, "", Access::read_write, Apply::live, kOpen,
     TNV_INT(telemetry.contour_ms), "TLM_CONTOUR period; 0 = off"},
    {0x0026, "tlm.spindle_ms", ParamType::u32, "ms", 0, 60000, "", Access::read_write, Apply::live, kOpen,
     TNV_INT(telemetry.spindle_ms), "TLM_SPINDLE period; 0 = off"},
    {0x0030, "motion.circle_ramp_s", ParamType::f32, "s", 0.001, 10, "", Access::read_write, Apply::live, kOpen,
     TNV_REAL(motion.circle_ramp_s), "feed ramp at the start and end of a circle"},
    {0x0031, "motion.circle_dwell_s", ParamType::f32, "s", 0, 60, "", Access::read_write, Apply::live, kOpen,
     TNV_REAL(motion.circle_dwell_s), "servo-on hold before a circle starts"},
    {0x0032, "motion.move_ramp_s", ParamType::f32, "s", 0.001, 10, "", Access::read_write, Apply::live, kOpen,
     TNV_REAL(motion.move_ramp_s), "speed ramp of a point-to-point move"},
    {0x0033, "motion.move_dwell_s", ParamType::f32, "s", 0, 60, "", Access::read_write, Apply::live, kOpen,
     TNV_REAL(motion.move_dwell_s), "servo-on hold before a move starts"},
    {0x0034, "path.tolerance_mm", ParamType::f32, "mm", kPathToleranceMinMm, kPathToleranceMaxMm, "",
     Access::read_write, Apply::idle, kOpen, TNV_REAL(firmware.path_tolerance_mm),
     "programs: corner blends and arc lag stay within this of the programmed path (docs/motion.md)"},
    {0x0040, "capture.channels", ParamType::u32, "", 0, channel_mask_low(kAllCaptureChannels), "", Access::read_write,
     Apply::live, kOpen, TNV_INT(capture.channels),
     "channel bit mask, channels 0-31 (capture_channels); busy while a capture is armed; an arm with no channel in it "
     "or capture.channels_high is refused (out_of_range)"},
    {0x0041, "capture.trigger", ParamType::enumeration, "", 0, 2, "0=immediate 1=motion 2=fault", Access::read_write,
     Apply::live, kOpen, TNV_INT(capture.trigger), "when recording starts"},
    {0x0042, "capture.decimation", ParamType::u32, "tick", 1, 255, "", Access::read_write, Apply::live, kOpen,
     TNV_INT(capture.decimation), "ticks per recorded sample"},
    {0x0043, "capture.channels_high", ParamType::u32, "", 0, channel_mask_high(kAllCaptureChannels), "",
     Access::read_write, Apply::live, kOpen, TNV_INT(capture.channels_high),
     "channel bit mask, channels 32-63 (bit n: channel 32 + n); busy while a capture is armed"},
    {0x0044, "excite.f_min_hz", ParamType::f32, "Hz", kExcitationMinFreqHz, kExcitationMaxFreqHz, "",
     Access::read_write, Apply::live, kOpen, TNV_REAL(excite.f_min_hz),
     "EXCITE sweep / multisine: lowest frequency (the multisine's period is 1 / f_min)"},
    {0x0045, "excite.f_max_hz", ParamType::f32, "Hz", kExcitationMinFreqHz, kExcitationMaxFreqHz, "",
     Access::read_write, Apply::live, kOpen, TNV_REAL(excite.f_max_hz),
     "EXCITE sweep / multisine: highest frequency (> f_min)"},
    {0x0046, "excite.tones", ParamType::u32, "", 1, kMaxMultisineTones, "", Access::read_write, Apply::live, kOpen,
     TNV_INT(excite.tones), "EXCITE multisine: number of log-spaced tones (that many harmonics of 1 / period in the band)"},
    {0x0047, "excite.carrier_mm_s", ParamType::f32, "mm/s", -kExcitationMaxCarrierMmS, kExcitationMaxCarrierMmS, "",
     Access::read_write, Apply::live, kOpen, TNV_REAL(excite.carrier_mm_s),
     "EXCITE sweep / multisine: the holding reference moves at this speed through the drive phase, ramped in "
     "and out over 50 ms (0: a standing table; the travel must stay inside the soft limits)"},
    {0x0048, "force.n_per_volt", ParamType::f32, "N/V", -1e6, 1e6, "", Access::read_write, Apply::live, kOpen,
     TNV_REAL(firmware.force_sensor.n_per_volt), "force-sensor scale (ADC volts to N)"},
    {0x0050, "supervisor.max_missed_ticks", ParamType::u32, "tick", 0, kMissedTicksMax, "", Access::read_write, Apply::idle,
     kSafety, TNV_INT(firmware.supervisor.max_consecutive_missed_ticks), "consecutive lost ticks before a fault"},
    // The S3 force loop as the programs' feed-override source (arsc_source_params.hpp). Not safety
    // parameters: the loop only sets a feed override, and the planner keeps every axis limit under any.
    // Homing: ordinary parameters; the commissioning set (docs/safety.md) is unchanged (docs/notes.md "Homing").
    {0x0058, "homing.required", ParamType::boolean, "", 0, 1, kOnOff, Access::read_write, Apply::idle, kOpen,
     TNV_INT(firmware.homing_required),
     "circle, move and programs refused until the axes they move are homed; off by default, on at commissioning"},
    {0x0060, "arsc.enable", ParamType::boolean, "", 0, 1, kOnOff, Access::read_write, Apply::idle, kOpen,
     TNV_INT(firmware.arsc.enabled), "force loop sets the feed override of every program"},
    {0x0061, "arsc.force_ref_n", ParamType::f32, "N", 0, kArscForceMaxN, "", Access::read_write, Apply::live, kOpen,
     TNV_REAL(firmware.arsc.force_ref_n), "reference force f* (S3: 150 N); live"},
    {0x0062, "arsc.period_ticks", ParamType::u32, "tick", 1, arsc::kMaxArscPeriodTicks, "", Access::read_write,
     Apply::idle, kOpen, TNV_INT(firmware.arsc.period_ticks), "the loop's period in ticks (S3: 150)"},
    {0x0063, "arsc.pole_re_rad_s", ParamType::f32, "rad/s", -kArscPoleMaxRadS, -1e-3, "", Access::read_write,
     Apply::idle, kOpen, TNV_REAL(firmware.arsc.pole_re_rad_s), "force-loop pole pair, real part (< 0)"},
    {0x0064, "arsc.pole_im_rad_s", ParamType::f32, "rad/s", 0, kArscPoleMaxRadS, "", Access::read_write, Apply::idle,
     kOpen, TNV_REAL(firmware.arsc.pole_im_rad_s), "force-loop pole pair, imaginary part; 0 = a double real pole"},
    {0x0065, "arsc.force_time_constant_s", ParamType::f32, "s", 1e-3, 10, "", Access::read_write, Apply::idle, kOpen,
     TNV_REAL(firmware.arsc.force_time_constant_s), "model: the cut's force lag T_f (S3 eq. 28)"},
    {0x0066, "arsc.cutting_gain_n_per_mm_s", ParamType::f32, "N*s/mm", 1e-3, 1e4, "", Access::read_write,
     Apply::idle, kOpen, TNV_REAL(firmware.arsc.cutting_gain_n_per_mm_s),
     "model: force per path feed at the start of a cut (G = K delta)"},
    {0x0067, "arsc.drive_time_constant_s", ParamType::f32, "s", 1e-4, 1, "", Access::read_write, Apply::idle, kOpen,
     TNV_REAL(firmware.arsc.drive_time_constant_s), "model: lag from a feed command to the table's feed"},
    {0x0068, "arsc.memory_s", ParamType::f32, "s", 1e-3, 100, "", Access::read_write, Apply::idle, kOpen,
     TNV_REAL(firmware.arsc.memory_s), "cutting-gain estimator memory (forgetting exp(-T / memory))"},
    {0x0069, "arsc.gain_min_ratio", ParamType::f32, "", 1e-3, 1, "", Access::read_write, Apply::idle, kOpen,
     TNV_REAL(firmware.arsc.gain_min_ratio), "estimate kept >= this x the start gain"},
    {0x006A, "arsc.gain_max_ratio", ParamType::f32, "", 1, 1e3, "", Access::read_write, Apply::idle, kOpen,
     TNV_REAL(firmware.arsc.gain_max_ratio), "estimate kept <= this x the start gain"},
    {0x006B, "arsc.adapt", ParamType::boolean, "", 0, 1, kOnOff, Access::read_write, Apply::idle, kOpen,
     TNV_INT(firmware.arsc.adapt), "estimate the cutting gain on line (off: fixed gains)"},
    {0x006C, "arsc.override_min", ParamType::f32, "", 0, motion::kMaxFeedOverride, "", Access::read_write,
     Apply::idle, kOpen, TNV_REAL(firmware.arsc.override_min), "lowest feed override the loop sets"},
    {0x006D, "arsc.override_max", ParamType::f32, "", 0, motion::kMaxFeedOverride, "", Access::read_write,
     Apply::idle, kOpen, TNV_REAL(firmware.arsc.override_max), "highest feed override the loop sets (> override_min)"},
    {0x006E, "arsc.soft_start_s", ParamType::f32, "s", 0, 60, "", Access::read_write, Apply::idle, kOpen,
     TNV_REAL(firmware.arsc.soft_start_s), "f* ramps from 0 over this long when a cut starts"},
    {0x006F, "tlm.arsc_ms", ParamType::u32, "ms", 0, 60000, "", Access::read_write, Apply::live, kOpen,
     TNV_INT(telemetry.arsc_ms), "TLM_ARSC period; 0 = off"},
    TNV_BORE_PARAMS,
    // The spindle (firmware/spindle/spindle_params.hpp): only while it is stopped and still (spindle_running
    // otherwise; the table at rest too, as every idle parameter); inside the drive's own limits.
    {0x0080, "spindle.max_rpm", ParamType::f32, "rpm", 1, kSpindleDriveFullScaleRpm, "", Access::read_write,
     Apply::idle, kOpen, TNV_REAL(firmware.spindle.max_rpm), "a start or speed above this is refused"},
    {0x0081, "spindle.accel_rpm_s", ParamType::f32, "rpm/s", 1, kSpindleDriveAccelRpmS, "", Access::read_write,
     Apply::idle, kOpen, TNV_REAL(firmware.spindle.accel_rpm_s), "the command's ramp (the drive's limit: 6000)"},
    {0x0082, "spindle.at_speed_fraction", ParamType::f32, "", 0.001, 0.5, "", Access::read_write, Apply::idle, kOpen,
     TNV_REAL(firmware.spindle.at_speed_fraction), "at speed: |n - n_cmd| within this fraction of n_cmd ..."},
    {0x0083, "spindle.at_speed_floor_rpm", ParamType::f32, "rpm", 0, 1000, "", Access::read_write, Apply::idle, kOpen,
     TNV_REAL(firmware.spindle.at_speed_floor_rpm), "... or within this, whichever is larger"},
    {0x0084, "spindle.at_speed_ticks", ParamType::u32, "tick", 1, 10000, "", Access::read_write, Apply::idle, kOpen,
     TNV_INT(firmware.spindle.at_speed_ticks), "... for this many ticks in a row: then feed moves may start"},
    {0x0085, "spindle.standstill_rpm", ParamType::f32, "rpm", 0.1, 500, "", Access::read_write, Apply::idle, kOpen,
     TNV_REAL(firmware.spindle.standstill_rpm), "a stopping spindle at or below this is still (enable dropped)"},
// One block of rows per axis of TNV_AXES: ids (index + 1) << 8, names "<axis>.".
#define TNV_AXIS_PARAM_BLOCK(name, ...) \
  TNV_AXIS_PARAMS(hal::index(hal::Axis::name), axis_param_base(hal::Axis::name), #name "."),
    TNV_AXES(TNV_AXIS_PARAM_BLOCK)
#undef TNV_AXIS_PARAM_BLOCK
};

#undef TNV_AXIS_PARAMS
#undef TNV_TURN_ERROR_ROW
#undef TNV_BORE_PARAMS
#undef TNV_BORE_LEARNED
#undef TNV_REAL
#undef TNV_INT
#undef TNV_RO
#undef TNV_SCALED
#undef TNV_MEMBER

constexpr bool sorted_unique() {
  for (std::size_t i = 1; i < std::size(kParams); ++i)
    if (kParams[i].id <= kParams[i - 1].id) return false;
  return true;
}
static_assert(sorted_unique(), "parameter ids must be sorted and unique");

std::size_t param_count() noexcept { return std::size(kParams); }

}  // namespace

std::uint16_t first_safety_change(const NodeSettings& live, const NodeSettings& next) noexcept {
  for (const ParamDef& p : kParams)
    if (safety_param(p) && to_wire(p, p.get(live)) != to_wire(p, p.get(next))) return p.id;
  return 0;
}

void keep_safety_params(const NodeSettings& from, NodeSettings& to) noexcept {
  for (const ParamDef& p : kParams)
    if (safety_param(p)) p.set(to, p.get(from));
}

std::size_t differing_params(const NodeSettings& a, const NodeSettings& b, std::size_t stop_at) noexcept {
  std::size_t n = 0;
  for (const ParamDef& p : kParams)
    if (p.access == Access::read_write && p.get(a) != p.get(b) && ++n >= stop_at) break;
  return n;
}

std::span<const ParamDef> param_table() noexcept { return kParams; }

const ParamDef* find_param(std::uint16_t id) noexcept {
  std::size_t lo = 0;
  std::size_t hi = std::size(kParams);
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (kParams[mid].id < id) lo = mid + 1;
    else hi = mid;
  }
  return lo < std::size(kParams) && kParams[lo].id == id ? &kParams[lo] : nullptr;
}

const ParamDef* find_param(const char* name) noexcept {
  for (const ParamDef& p : kParams)
    if (std::strcmp(p.name, name) == 0) return &p;
  return nullptr;
}

ErrorCode check_value(const ParamDef& p, double value) noexcept {
  if (p.access == Access::read_only) return ErrorCode::read_only;
  if (!std::isfinite(value)) return ErrorCode::not_finite;
  if (value < p.min || value > p.max) return ErrorCode::out_of_range;
  if (p.type != ParamType::f32 && value != std::floor(value)) return ErrorCode::out_of_range;
  if (p.allowed != nullptr && !p.allowed(value)) return ErrorCode::out_of_range;
  return ErrorCode::ok;
}

std::uint32_t to_wire(const ParamDef& p, double value) noexcept {
  switch (p.type) {
    case ParamType::f32: return float_bits(static_cast<float>(value));
    case ParamType::i32:
      if (!(value >= -2147483648.0 && value <= 2147483647.0)) return 0;
      return static_cast<std::uint32_t>(static_cast<std::int32_t>(value));
    case ParamType::u32:
    case ParamType::boolean:
    case ParamType::enumeration:
      if (!(value >= 0.0 && value <= 4294967295.0)) return 0;
      return static_cast<std::uint32_t>(value);
  }
  return 0;
}

double from_wire(const ParamDef& p, std::uint32_t raw) noexcept {
  switch (p.type) {
    case ParamType::f32: return static_cast<double>(bits_float(raw));
    case ParamType::i32: return static_cast<double>(static_cast<std::int32_t>(raw));
    case ParamType::u32:
    case ParamType::boolean:
    case ParamType::enumeration: return static_cast<double>(raw);
  }
  return 0.0;
}

namespace {

// The sections a per-axis validation error names ("axis x: shaper").
#define TNV_AXIS_SECTION(name, ...) "axis " #name ": shaper",
constexpr const char* kAxisShaperSection[] = {TNV_AXES(TNV_AXIS_SECTION)};
#undef TNV_AXIS_SECTION
#define TNV_AXIS_SECTION(name, ...) "axis " #name ": limits",
constexpr const char* kAxisLimitsSection[] = {TNV_AXES(TNV_AXIS_SECTION)};
#undef TNV_AXIS_SECTION

// The parameter whose member `member` is in `s` (a validation error's
// offending member); 0 when it is none of them.
std::uint16_t param_at(const NodeSettings& s, const void* member) noexcept {
  if (member == nullptr) return 0;
  for (const ParamDef& p : kParams)
    if (p.member != nullptr && p.member(s) == member) return p.id;
  return 0;
}

SettingsCheck validate_parts(const NodeSettings& s, const NodeSettings* base) noexcept {
  if (base != nullptr && same_bytes(s, *base)) return {};
  for (const ParamDef& p : kParams) {
    if (p.access == Access::read_only) continue;
    if (check_value(p, p.get(s)) != ErrorCode::ok) return {false, p.id, p.name, "outside the parameter's range"};
  }
  const ConfigError e = base != nullptr ? validate(s.firmware, base->firmware) : validate(s.firmware);
  if (!e.ok()) return {false, param_at(s, e.member), e.section, e.reason};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    if (base == nullptr || !same_bytes(s.shaper[i].spec, base->shaper[i].spec))
      if (const ParamCheck c = validate(s.shaper[i].spec); !c.ok)
        return {false, static_cast<std::uint16_t>(axis_param_base(hal::axis_from_index(i)) + 0x41),
                kAxisShaperSection[i], c.reason};
    const AxisLimits& lim = s.firmware.supervisor.axis[i];
    if (!(lim.position_min_mm < lim.position_max_mm))
      return {false, static_cast<std::uint16_t>(axis_param_base(hal::axis_from_index(i)) + 0x50),
              kAxisLimitsSection[i], "position_min_mm must be below position_max_mm"};
  }
  if (!(s.excite.f_min_hz < s.excite.f_max_hz)) return {false, 0x0045, "excite", "f_max_hz must be above f_min_hz"};
  if (s.excite.tones > multisine_tone_capacity(s.excite.f_min_hz, s.excite.f_max_hz, kControlPeriod_s))
    return {false, 0x0046, "excite", "more tones than harmonics of 1 / period between f_min_hz and f_max_hz"};
  if (base == nullptr || !same_bytes(s.bore, base->bore))
    if (const ParamCheck c = validate(s.bore); !c.ok) return {false, bore_param_for(c.field), "bore", c.reason};
  // The learned state is no parameter; a damaged one fails the set as a whole.
  if (base == nullptr || !same_bytes(s.bore_state, base->bore_state))
    if (const ParamCheck c = validate(s.bore_state); !c.ok) return {false, 0, "bore: learned state", c.reason};
  return {};
}

}  // namespace

SettingsCheck validate(const NodeSettings& s) noexcept { return validate_parts(s, nullptr); }

SettingsCheck validate(const NodeSettings& s, const NodeSettings& valid_base) noexcept {
  return validate_parts(s, &valid_base);
}

}  // namespace tnv::fw::can
