#pragma once
// Everything that describes one emulated experiment. Defaults are the
// reference plant (shared design notes: reference-plant.md); every field
// is settable from a TOML scenario file (scenario_file.hpp).
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "emulator/fault_schedule.hpp"
#include "hal/axis.hpp"

namespace tnv::emu {

struct AxisPlantParams {
  double tau_s = 0.005360;       // speed-loop time constant
  double gain = 1.0;             // K: table speed per commanded speed
  double coulomb_mm_s = 1.5;     // f_c
  double stiction_mm_s = 3.0;    // f_s
  double stribeck_mm_s = 0.1;    // v_s
  double mode_hz = 0.0;          // optional structural mode, 0 = none
  double mode_zeta = 0.0;
  // Ball screw between motor (encoder) and table (screw_transmission.hpp); all off by default.
  double backlash_um = 0.0;          // lost motion on a reversal
  double lead_error_um_per_m = 0.0;  // cumulative lead error, table minus motor side per metre
  double pitch_error_um = 0.0;       // periodic lead error, amplitude
  double pitch_period_mm = 10.0;     // its period along the screw (one turn of the 10 mm lead)
  double accel_limit_mm_s2 = 0.0;    // the servopack's current limit as |dv/dt|; 0 = none
};

struct CuttingParams {
  bool enabled = false;
  double spindle_rpm = 900.0;
  int flutes = 2;
  double mean_mm_s = 0.6;       // c_m
  double amplitude_mm_s = 0.6;  // c_a
  double exponent = 0.75;       // Kienzle exponent on (900/S)
  double phase_rad = 0.0;       // phi_0
};

struct EncoderParams {
  int counts_per_rev = 24000;  // after x4 decoding
  double lead_mm = 10.0;
  // count = round(p/q + offset), per axis ([encoder] offset_counts_<axis>).
  std::array<double, hal::kAxisCount> axis_offset_counts{};
  double offset_counts(hal::Axis axis) const noexcept { return axis_offset_counts[hal::index(axis)]; }
  double count_mm() const noexcept { return lead_mm / counts_per_rev; }
};

struct DacParams {
  int bits = 12;
  double full_scale_v = 10.0;
  double rpm_at_full_scale = 1000.0;
};

struct ForceSensorParams {
  double volts_per_mm_s = 1.0;  // ADC input volts per mm/s of cutting disturbance magnitude
  double volts_per_n = 1.0 / 30.0;  // ADC input volts per N of milling force (when [milling] is on)
};

// Depth of cut over time, S3 Fig. 4: start -> peak over rise_s, back over fall_s.
struct DepthProfile {
  double start_mm = 0.2;
  double peak_mm = 1.0;
  double rise_s = 15.0;
  double fall_s = 15.0;
};

// S3 end-milling process on X (emulator/milling_force.hpp). Off by default.
struct MillingParams {
  bool enabled = false;
  double time_constant_s = 0.20;       // T_f, S3
  double force_n_per_mm_mm_s = 15.0;   // K: 150 N at 0.8 mm and 12.5 mm/s (S3 experiment)
  double feed_load_mm_s_per_n = 0.004;  // table-speed disturbance per N, opposing the feed
  DepthProfile depth{};
};

// One axis' switches and marks on the board.
struct BoardAxisParams {
  // Home switch (INPUTS), actuated by the table: asserted at and beyond
  // home_mm on the home_side (-1: at and below, +1: at and above). Absent by
  // default (the input reads 0): a homing cycle then finds no switch.
  bool home_switch = false;
  double home_mm = -20.0;
  int home_side = -1;
  // Encoder index mark: once per motor revolution at this motor angle; angle
  // 0 is motor-side position 0 (the plant state p modulo the lead). The board
  // latches the count there (INDEX_<axis>). Always present, like on the encoder.
  double index_deg = 0.0;
  // Hardware limit switches (when BoardParams::limit_switches) at these table positions.
  double limit_min_mm = -200.0;
  double limit_max_mm = 200.0;
  // Power-up position: the table starts this far from the circle's start
  // point (circle.radius_mm, 0), the head this far from [plant.z] start_mm
  // (motor side and table together).
  double power_up_offset_mm = 0.0;
};

// Each axis' law and switches by default (the reference plant; a switch
// over the axes without a default: a new axis of TNV_AXES states its own).
inline constexpr AxisPlantParams kYAxisLaw{.tau_s = 0.007122};
inline constexpr AxisPlantParams kZAxisLaw{
    .tau_s = 0.009, .gain = 1.0, .coulomb_mm_s = 2.0, .stiction_mm_s = 4.0, .stribeck_mm_s = 0.1};
constexpr std::array<AxisPlantParams, hal::kAxisCount> default_axis_plants() noexcept {
  std::array<AxisPlantParams, hal::kAxisCount> out{};
  for (const hal::Axis axis : hal::kAxes) {
    switch (axis) {
      case hal::Axis::x: out[hal::index(axis)] = AxisPlantParams{}; break;
      case hal::Axis::y: out[hal::index(axis)] = kYAxisLaw; break;
      case hal::Axis::z: out[hal::index(axis)] = kZAxisLaw; break;
    }
  }
  return out;
}
// X and Y: no home switch unless a scenario fits one. Z: the reference
// plant's switch at the top of the head's travel (actuated at and above
// 0 mm), and its limit switches (when on) halfway between the travel's ends
// and the hard stops.
constexpr std::array<BoardAxisParams, hal::kAxisCount> default_board_axes() noexcept {
  std::array<BoardAxisParams, hal::kAxisCount> out{};
  for (const hal::Axis axis : hal::kAxes) {
    switch (axis) {
      case hal::Axis::x:
      case hal::Axis::y: break;
      case hal::Axis::z:
        out[hal::index(axis)] = BoardAxisParams{
            .home_switch = true, .home_mm = 0.0, .home_side = 1, .limit_min_mm = -302.5, .limit_max_mm = 2.5};
        break;
    }
  }
  return out;
}

struct BoardParams {
  std::uint32_t clock_start = 0;  // initial value of the free-running 10 MHz counter
  // Hardware limit switches at each axis' limit_min_mm / limit_max_mm (INPUTS
  // bits, ORed with the bench and the fault schedule); off by default.
  bool limit_switches = false;
  // Per axis, in TNV_AXES order; the file's keys are <field>_<axis> (home_x_mm,
  // home_switch_y, ...: scenario_file.cpp).
  std::array<BoardAxisParams, hal::kAxisCount> axis = default_board_axes();
  bool home_switch(hal::Axis a) const noexcept { return axis[hal::index(a)].home_switch; }
  double home_mm(hal::Axis a) const noexcept { return axis[hal::index(a)].home_mm; }
  int home_side(hal::Axis a) const noexcept { return axis[hal::index(a)].home_side; }
  double index_deg(hal::Axis a) const noexcept { return axis[hal::index(a)].index_deg; }
  double power_up_offset_mm(hal::Axis a) const noexcept { return axis[hal::index(a)].power_up_offset_mm; }
};

// Sensor and actuator imperfections, seeded (noise_stream.hpp); all off by default.
struct NoiseParams {
  std::uint32_t seed = 0;
  double force_adc_v_rms = 0.0;       // Gaussian, at the force ADC's input
  double accel_g_rms = 0.0;           // Gaussian, per accelerometer axis
  double accel_bias_g = 0.0;          // constant, both accelerometer axes
  double dac_offset_v = 0.0;          // added to both speed DACs' output volts
  double dac_gain_error = 0.0;        // relative: the DACs output (1 + gain_error) times the ideal volts
  double encoder_glitch_per_s = 0.0;  // Poisson rate of miscounts, per encoder
  int encoder_glitch_counts = 1;      // counts each miscount adds (sign random), kept by the decoder
  // The post-process bore gauge of the S4 boring studies (not sampled at the tick):
  double bore_gauge_um_rms = 0.0;         // Gaussian, its repeatability, on the diametral bore error
  double bore_gauge_resolution_um = 0.0;  // its reading's step; 0 = a continuous reading
  bool any_sample_noise() const noexcept {  // anything added at the tick latch
    return force_adc_v_rms != 0.0 || accel_g_rms != 0.0 || accel_bias_g != 0.0 || encoder_glitch_per_s != 0.0;
  }
};

// The register transport between the firmware's CPU and the board (output_transport.hpp); off by default.
struct IoParams {
  double read_latency_us = 0.0;   // tick latch -> the snapshot read completes
  double write_latency_us = 0.0;  // the firmware's output write issued -> it lands on the board
  double jitter_us = 0.0;         // uniform 0..jitter_us added to each read and each write (seeded)
  bool enabled() const noexcept { return read_latency_us != 0.0 || write_latency_us != 0.0 || jitter_us != 0.0; }
};

struct CircleParams {
  double radius_mm = 6.0;
  double feed_mm_s = 2.0;  // F, also the programmed feed of the cutting model
  double ramp_s = 0.1;     // raised-cosine feed ramp at start and end
  double dwell_s = 0.5;    // servo-on dwell before the start
};

// The machining centre beyond the XY table (docs/machine.md): the Z axis,
// the spindle, the tool, the stock and the processes that act where the
// tool is. Built and tested as emulator classes; not yet on the I/O board.

// Z: the axis law of AxisPlantParams plus the head's uncompensated weight
// (reference plant "Z axis"). Positions are the spindle nose in machine
// coordinates, 0 at the top.
// Its law (tau_Z, K, friction) is Scenario::plant's Z entry, [plant.z] like
// every axis' (kZAxisLaw below); its home switch is the board's (home_z_mm).
struct ZAxisParams {
  double gravity_mm_s = -1.0;       // d_g: a constant pull toward -Z
  double travel_top_mm = 0.0;       // the travel's ends
  double travel_bottom_mm = -300.0;
  double overtravel_mm = 5.0;       // hard stops this far beyond each end of the travel
  double start_mm = -25.0;          // where the head stands at power-up (plus [board] power_up_offset_z_mm)
};

// The spindle drive and its encoder (reference plant "Spindle").
struct SpindleParams {
  double tau_s = 0.20;                  // tau_sp
  int dac_bits = 12;                    // its speed DAC, offset binary, +-full_scale_v
  double full_scale_v = 10.0;
  double rpm_at_full_scale = 12'000.0;  // K_sp: rpm at +full scale; the sign is the direction
  double accel_limit_rpm_s = 6'000.0;   // a_sp, the drive's current limit
  double droop_rpm_per_n = 0.2;         // k_d
  int encoder_counts_per_rev = 4096;    // after x4 decoding
  double index_deg = 0.0;               // angle of the index mark
};

// S3's reference cut (S3: a_p 1 mm, f_z 0.05 mm, 3/8" end mill, 4 flutes: 150 N).
inline constexpr double kReferenceForceN = 150.0;
inline constexpr double kReferenceDepthMm = 1.0;
inline constexpr double kReferenceFeedPerToothMm = 0.05;
inline constexpr double kReferenceDiameterMm = 9.525;
// K_c that gives `force_n` at a_p, f_z and D: F = K_c a_p f_z^0.75 D^0.25 solved for K_c
// (defined beside the force law, tool_milling_force.cpp).
double specific_cutting_force_n_mm2(double force_n, double depth_mm, double feed_per_tooth_mm, double diameter_mm);

// The tool in the spindle.
struct ToolParams {
  double diameter_mm = kReferenceDiameterMm;  // D
  int flutes = 4;                             // N
  double flute_length_mm = 20.0;              // the longest a_p it can take
  double length_mm = 125.0;                   // spindle nose to tool point (the tool table's length offset)
};

// The block of stock (reference plant "Stock"): top face and XY rectangle.
// Default rectangle: the whole table (unbounded). Off by default: a
// scenario without a stock has nothing on the table (the probe never trips,
// emulator::Machine cuts nothing); with it on, emu::Machine cuts where the
// tool is ([tool], [tool_cut]) and the probe trips on it.
// A hole the part has before the program runs ([[stock.hole]]): a
// cylinder down from the stock top, depth_mm deep or through (to the table).
struct StockHole {
  double x_mm = 0.0;  // its axis, machine coordinates
  double y_mm = 0.0;
  double diameter_mm = 0.0;
  double depth_mm = std::numeric_limits<double>::infinity();  // infinity: through
};

inline constexpr std::size_t kMaxStockHoles = 64;  // each cell's first height looks at every hole

struct StockParams {
  bool enabled = false;    // [stock] enabled = true: the block is on the table
  double top_mm = -150.0;  // z_top, machine coordinates
  double x_min_mm = -std::numeric_limits<double>::infinity();
  double x_max_mm = std::numeric_limits<double>::infinity();
  double y_min_mm = -std::numeric_limits<double>::infinity();
  double y_max_mm = std::numeric_limits<double>::infinity();
  std::vector<StockHole> holes{};  // [[stock.hole]]: pre-drilled holes
};

// The milling force where the tool is (reference plant "Stock, and cutting where the tool is").
struct ToolCutParams {
  double k_c_n_mm2 = specific_cutting_force_n_mm2(kReferenceForceN, kReferenceDepthMm, kReferenceFeedPerToothMm,
                                                  kReferenceDiameterMm);
  double time_constant_s = 0.20;          // T_f, S3
  double stiffness_n_per_mm_s = 100.0;    // each XY drive: newtons per mm/s of table-speed disturbance
  double crash_speed_fraction = 0.5;      // engaging below this fraction of the commanded speed is a crash
  double max_feed_per_tooth_mm = 1.0;     // f_z is capped here (a slow spindle's chip is bounded by the crash)
};

// S4 on real axes (reference plant "Boring (S4, on real axes)").
struct BoringAxesParams {
  bool enabled = false;                  // [boring] enabled = true: emu::Machine bores where the tool is (needs [stock])
  double overhang_at_top_mm = 40.0;      // L0: overhang with the tool point at the stock top
  double gauge_top_depth_mm = 0.0;       // depths below the stock top the gauge reads after a part
  double gauge_bottom_depth_mm = 270.0;  // (L = 40 and 310 mm, the S4 study's measuring overhangs)
  double sigma_d_um = 16.231;            // process noise on the deflection, S4 Table 1
  int change_at_1 = 11;                  // S4 section 5: parameter sets change at these parts
  int change_at_2 = 21;
};

// Touch probe: triggered when the tool point is within tip_radius_mm of the stock.
struct ProbeParams {
  double tip_radius_mm = 0.0;
};

struct Scenario {
  std::string name = "default";
  std::array<AxisPlantParams, hal::kAxisCount> plant = default_axis_plants();
  CuttingParams cutting{};
  EncoderParams encoder{};
  DacParams dac{};
  ForceSensorParams force_sensor{};
  MillingParams milling{};
  BoardParams board{};
  NoiseParams noise{};
  IoParams io{};
  CircleParams circle{};
  ZAxisParams z_axis{};        // [plant.z]
  SpindleParams spindle{};     // [spindle]
  ToolParams tool{};           // [tool]
  StockParams stock{};         // [stock]
  ToolCutParams tool_cut{};    // [tool_cut]
  BoringAxesParams boring{};   // [boring]
  ProbeParams probe{};         // [probe]
  std::vector<FaultSpec> faults{};  // [[fault]]: injected on schedule (fault_schedule.hpp)
};

// Where an axis stands at power-up (motor side and table together): the XY
// table at the circle's start point (R, 0), the head at [plant.z] start_mm,
// each moved by its [board] power_up_offset_<axis>_mm. One case per axis and
// no default: a new axis of TNV_AXES states its own.
inline double power_up_position_mm(const Scenario& s, hal::Axis axis) noexcept {
  const double offset_mm = s.board.power_up_offset_mm(axis);
  switch (axis) {
    case hal::Axis::x: return s.circle.radius_mm + offset_mm;
    case hal::Axis::y: return offset_mm;
    case hal::Axis::z: return s.z_axis.start_mm + offset_mm;
  }
  return offset_mm;
}

}  // namespace tnv::emu
