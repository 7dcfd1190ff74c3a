#include "emulator/scenario_keys.hpp"

#include <cstddef>
#include <functional>
#include <type_traits>
#include <utility>

#include "emulator/scenario_validation.hpp"
#include "emulator/substep_timing.hpp"
#include "hal/axis.hpp"

namespace tnv::emu {

namespace {

using namespace key_rule;

// A table of the TNV-40 class travels well under 1 m: switches beyond +-500 mm are typing errors.
constexpr double kSwitchRangeMm = 500.0;
// A machining centre of the TNV-40 class: Z travel well under 1 m.
constexpr double kMachineRangeMm = 1000.0;

// The rows of one section whose members live in a T (a struct of the Scenario).
template <class T>
class Section {
 public:
  Section(std::vector<ScenarioKey>& rows, std::string name, std::function<T&(Scenario&)> get)
      : rows_(rows), name_(std::move(name)), get_(std::move(get)) {}

  // A number: its rule is part of its row. `field` is a member pointer or a T& -> member& function.
  template <class F>
    requires std::is_same_v<std::remove_cvref_t<std::invoke_result_t<F, T&>>, double> ||
             std::is_same_v<std::remove_cvref_t<std::invoke_result_t<F, T&>>, int>
  void key(std::string name, F field, KeyRule rule) {
    add(std::move(name), field, std::move(rule));
  }
  // A boolean, a string or a uint32: the type is the range.
  template <class F>
    requires std::is_same_v<std::remove_cvref_t<std::invoke_result_t<F, T&>>, bool> ||
             std::is_same_v<std::remove_cvref_t<std::invoke_result_t<F, T&>>, std::string> ||
             std::is_same_v<std::remove_cvref_t<std::invoke_result_t<F, T&>>, std::uint32_t>
  void key(std::string name, F field) {
    add(std::move(name), field, {});
  }

 private:
  template <class F>
  void add(std::string name, F field, KeyRule rule) {
    rows_.push_back(ScenarioKey{name_, std::move(name),
                                [get = get_, field](Scenario& s) -> FieldTarget { return &std::invoke(field, get(s)); },
                                std::move(rule)});
  }

  std::vector<ScenarioKey>& rows_;
  std::string name_;
  std::function<T&(Scenario&)> get_;
};

// The axis law's keys, on X, Y and Z.
void add_axis_law(Section<AxisPlantParams>& p) {
  using P = AxisPlantParams;
  p.key("tau_s", &P::tau_s, positive().plausible(1e-4, 1.0, "a servo axis' speed loop settles in 0.1 ms to 1 s"));
  p.key("gain", &P::gain, positive().plausible(0.1, 10.0, "the drive's speed per commanded speed"));
  p.key("coulomb_mm_s", &P::coulomb_mm_s,
        non_negative().plausible(0.0, 1000.0, "friction above 1000 mm/s is no moving table (a jam is 200)"));
  p.key("stiction_mm_s", &P::stiction_mm_s,
        non_negative().plausible(0.0, 1000.0, "friction above 1000 mm/s is no moving table (a jam is 200)"));
  p.key("stribeck_mm_s", &P::stribeck_mm_s, positive().plausible(0.0, 1000.0, "the Stribeck speed of a table's guideways"));
  p.key("accel_limit_mm_s2", &P::accel_limit_mm_s2,
        zero_or_plausible(100.0, 1e6, "a servo axis' current-limited acceleration, 0.01 to 100 g"));
}

// Each axis' structural mode and ball screw.
void add_axis_extras(Section<AxisPlantParams>& p) {
  using P = AxisPlantParams;
  const double nyquist_hz = static_cast<double>(kSubstepsPerSecond) / 2.0;
  p.key("mode_hz", &P::mode_hz, below(nyquist_hz, "the sub-step Nyquist frequency " + format_number(nyquist_hz) + " Hz"));
  p.key("mode_zeta", &P::mode_zeta, below(1.0, "1"));
  // Beyond these the model is no servo table: the numbers would only make
  // the run fail later, far from the key that caused it.
  p.key("backlash_um", &P::backlash_um,
        plausible(0.0, 500.0, "a ball screw's lost motion: 0-5 um new, 10-50 um worn; past 0.5 mm the nut is broken"));
  p.key("lead_error_um_per_m", &P::lead_error_um_per_m,
        plausible(-1000.0, 1000.0, "a ball screw's cumulative lead error (ISO 3408-3 class C10 allows 700 um/m)"));
  p.key("pitch_error_um", &P::pitch_error_um,
        plausible(0.0, 100.0, "a ball screw's periodic lead error amplitude (C5 varies 8 um within a turn)"));
  p.key("pitch_period_mm", &P::pitch_period_mm, plausible(0.1, 1000.0, "a screw lead or a multiple of it"));
}

std::vector<ScenarioKey> build_table() {
  std::vector<ScenarioKey> rows;
  Section<Scenario> top(rows, "", [](Scenario& s) -> Scenario& { return s; });
  top.key("name", &Scenario::name);

  for (const hal::Axis axis : hal::kAxes) {
    const std::size_t i = hal::index(axis);
    Section<AxisPlantParams> p(rows, "plant." + std::string(hal::axis_label(axis)),
                               [i](Scenario& s) -> AxisPlantParams& { return s.plant[i]; });
    add_axis_law(p);
    add_axis_extras(p);
  }

  {
    using C = CuttingParams;
    Section<C> c(rows, "cutting", [](Scenario& s) -> C& { return s.cutting; });
    c.key("enabled", &C::enabled);
    c.key("spindle_rpm", &C::spindle_rpm, positive().plausible(1.0, 100'000.0, "a machining spindle's speed"));
    c.key("flutes", &C::flutes, at_least(1));
    c.key("mean_mm_s", &C::mean_mm_s, non_negative().plausible(0.0, 1000.0, "a cutting load as a table speed"));
    c.key("amplitude_mm_s", &C::amplitude_mm_s, non_negative().plausible(0.0, 1000.0, "a cutting load as a table speed"));
    c.key("exponent", &C::exponent, finite().plausible(-10.0, 10.0, "the spindle-speed law's exponent"));
    c.key("phase_rad", &C::phase_rad, finite());
  }
  {
    using E = EncoderParams;
    Section<E> e(rows, "encoder", [](Scenario& s) -> E& { return s.encoder; });
    e.key("counts_per_rev", &E::counts_per_rev,
          positive_multiple_of_4().plausible(4.0, 1e8, "a rotary encoder's counts per turn (x4)"));
    e.key("lead_mm", &E::lead_mm, positive().plausible(0.1, 100.0, "a ball screw's lead"));
    for (const hal::Axis axis : hal::kAxes) {
      const std::size_t i = hal::index(axis);
      e.key("offset_counts_" + std::string(hal::axis_label(axis)),
            [i](E& enc) -> double& { return enc.axis_offset_counts[i]; }, finite());
    }
  }
  {
    using B = BoardParams;
    Section<B> b(rows, "board", [](Scenario& s) -> B& { return s.board; });
    b.key("clock_start", &B::clock_start);
    b.key("limit_switches", &B::limit_switches);
    // Per axis: <field>_<axis>, or <field>_<axis>_<unit> where the field has a unit.
    for (const hal::Axis axis : hal::kAxes) {
      using A = BoardAxisParams;
      const std::size_t i = hal::index(axis);
      const std::string n = hal::axis_label(axis);
      Section<A> a(rows, "board", [i](Scenario& s) -> A& { return s.board.axis[i]; });
      a.key("home_switch_" + n, &A::home_switch);
      a.key("home_" + n + "_mm", &A::home_mm,
            plausible(-kSwitchRangeMm, kSwitchRangeMm, "a home switch on the table's travel"));
      a.key("home_" + n + "_side", &A::home_side,
            one_of(-1, 1, "-1 (asserted at and below home_" + n + "_mm) or 1 (at and above)"));
      a.key("index_" + n + "_deg", &A::index_deg, plausible(0.0, 360.0, "a motor angle in degrees"));
      a.key("limit_" + n + "_min_mm", &A::limit_min_mm,
            plausible(-kSwitchRangeMm, kSwitchRangeMm, "a limit switch on the table's travel"));
      a.key("limit_" + n + "_max_mm", &A::limit_max_mm,
            plausible(-kSwitchRangeMm, kSwitchRangeMm, "a limit switch on the table's travel"));
      a.key("power_up_offset_" + n + "_mm", &A::power_up_offset_mm,
            plausible(-kSwitchRangeMm, kSwitchRangeMm, "where the table stands at power-up, on its travel"));
    }
  }
  {
    using D = DacParams;
    Section<D> d(rows, "dac", [](Scenario& s) -> D& { return s.dac; });
    d.key("bits", &D::bits, int_range(8, 16));
    d.key("full_scale_v", &D::full_scale_v,
          positive().plausible(0.5, 50.0, "a servo's analogue speed reference (10 V class)"));
    d.key("rpm_at_full_scale", &D::rpm_at_full_scale, positive().plausible(1.0, 100'000.0, "a servo motor's speed"));
  }
  {
    using F = ForceSensorParams;
    Section<F> f(rows, "force_sensor", [](Scenario& s) -> F& { return s.force_sensor; });
    f.key("volts_per_mm_s", &F::volts_per_mm_s, non_negative().plausible(0.0, 1000.0, "a force sensor's output range"));
    f.key("volts_per_n", &F::volts_per_n, non_negative().plausible(0.0, 1000.0, "a force sensor's output range"));
  }
  {
    using M = MillingParams;
    Section<M> m(rows, "milling", [](Scenario& s) -> M& { return s.milling; });
    m.key("enabled", &M::enabled);
    m.key("time_constant_s", &M::time_constant_s,
          positive().plausible(1e-4, 100.0, "a cutting process' time constant"));
    m.key("force_n_per_mm_mm_s", &M::force_n_per_mm_mm_s, non_negative());
    m.key("feed_load_mm_s_per_n", &M::feed_load_mm_s_per_n, non_negative());
    using D = DepthProfile;
    Section<D> d(rows, "milling", [](Scenario& s) -> D& { return s.milling.depth; });
    d.key("depth_start_mm", &D::start_mm, non_negative().plausible(0.0, 100.0, "a depth of cut"));
    d.key("depth_peak_mm", &D::peak_mm, non_negative().plausible(0.0, 100.0, "a depth of cut"));
    d.key("rise_s", &D::rise_s, non_negative());
    d.key("fall_s", &D::fall_s, non_negative());
  }
  {
    // The vertical axis' own keys (z_axis_plant.hpp); its law is the list's [plant.z] above.
    using Z = ZAxisParams;
    Section<Z> z(rows, "plant.z", [](Scenario& s) -> Z& { return s.z_axis; });
    z.key("gravity_mm_s", &Z::gravity_mm_s,
          plausible(-100.0, 100.0, "what the counterbalance leaves of the head's weight, as a table speed"));
    z.key("travel_top_mm", &Z::travel_top_mm, plausible(-kMachineRangeMm, kMachineRangeMm, "machine coordinates"));
    z.key("travel_bottom_mm", &Z::travel_bottom_mm, plausible(-kMachineRangeMm, kMachineRangeMm, "machine coordinates"));
    z.key("overtravel_mm", &Z::overtravel_mm,
          plausible(0.0, 100.0, "the room between a travel end and its hard stop"));
    z.key("start_mm", &Z::start_mm, with_other_keys());  // within the travel
  }
  {
    using S = SpindleParams;
    Section<S> sp(rows, "spindle", [](Scenario& s) -> S& { return s.spindle; });
    sp.key("tau_s", &S::tau_s, plausible(1e-3, 10.0, "a spindle drive's speed loop settles in 1 ms to 10 s"));
    sp.key("dac_bits", &S::dac_bits, int_range(8, 16));
    sp.key("full_scale_v", &S::full_scale_v, plausible(0.5, 50.0, "a drive's analogue speed reference (10 V class)"));
    sp.key("rpm_at_full_scale", &S::rpm_at_full_scale, plausible(1.0, 100'000.0, "a machining spindle's speed"));
    sp.key("accel_limit_rpm_s", &S::accel_limit_rpm_s,
           plausible(1.0, 1e6, "a spindle drive's current-limited acceleration (thousands of rpm/s)"));
    sp.key("droop_rpm_per_n", &S::droop_rpm_per_n, plausible(0.0, 100.0, "speed lost per newton of cutting load"));
    sp.key("encoder_counts_per_rev", &S::encoder_counts_per_rev, positive_multiple_of_4().int_range(4, 1'000'000));
    sp.key("index_deg", &S::index_deg, plausible(0.0, 360.0, "a spindle angle in degrees"));
  }
  {
    using T = ToolParams;
    Section<T> t(rows, "tool", [](Scenario& s) -> T& { return s.tool; });
    t.key("diameter_mm", &T::diameter_mm, plausible(0.1, 100.0, "an end mill's diameter"));
    t.key("flutes", &T::flutes, int_range(1, 20));
    t.key("flute_length_mm", &T::flute_length_mm, plausible(0.1, 300.0, "an end mill's flute length"));
    t.key("length_mm", &T::length_mm, plausible(0.0, 500.0, "spindle nose to tool point"));
  }
  {
    using S = StockParams;
    Section<S> st(rows, "stock", [](Scenario& s) -> S& { return s.stock; });
    st.key("enabled", &S::enabled);
    st.key("top_mm", &S::top_mm, plausible(-kMachineRangeMm, kMachineRangeMm, "machine coordinates"));
    // The default rectangle is unbounded (the whole table): +-inf are allowed.
    st.key("x_min_mm", &S::x_min_mm, inf_or_plausible(-kMachineRangeMm, kMachineRangeMm, "machine coordinates"));
    st.key("x_max_mm", &S::x_max_mm, inf_or_plausible(-kMachineRangeMm, kMachineRangeMm, "machine coordinates"));
    st.key("y_min_mm", &S::y_min_mm, inf_or_plausible(-kMachineRangeMm, kMachineRangeMm, "machine coordinates"));
    st.key("y_max_mm", &S::y_max_mm, inf_or_plausible(-kMachineRangeMm, kMachineRangeMm, "machine coordinates"));
  }
  {
    using C = ToolCutParams;
    Section<C> c(rows, "tool_cut", [](Scenario& s) -> C& { return s.tool_cut; });
    c.key("k_c_n_mm2", &C::k_c_n_mm2,
          plausible(1.0, 20'000.0, "a specific cutting force (aluminium ~700, steel ~2000 N/mm^2)"));
    c.key("time_constant_s", &C::time_constant_s, plausible(1e-4, 100.0, "a cutting process' time constant"));
    c.key("stiffness_n_per_mm_s", &C::stiffness_n_per_mm_s,
          plausible(0.1, 1e6, "a drive's stiffness against a load, newtons per mm/s"));
    c.key("crash_speed_fraction", &C::crash_speed_fraction,
          plausible(0.0, 1.0, "a fraction of the commanded spindle speed"));
    c.key("max_feed_per_tooth_mm", &C::max_feed_per_tooth_mm, plausible(1e-3, 10.0, "a chip thickness"));
  }
  {
    using P = ProbeParams;
    Section<P> p(rows, "probe", [](Scenario& s) -> P& { return s.probe; });
    p.key("tip_radius_mm", &P::tip_radius_mm, plausible(0.0, 10.0, "a touch probe's stylus ball radius"));
  }
  {
    using B = BoringAxesParams;
    Section<B> b(rows, "boring", [](Scenario& s) -> B& { return s.boring; });
    b.key("enabled", &B::enabled);
    b.key("overhang_at_top_mm", &B::overhang_at_top_mm, plausible(1.0, 2000.0, "a boring bar's overhang"));
    b.key("gauge_top_depth_mm", &B::gauge_top_depth_mm,
          plausible(0.0, kMachineRangeMm, "a depth below the stock top"));
    b.key("gauge_bottom_depth_mm", &B::gauge_bottom_depth_mm,
          plausible(0.0, kMachineRangeMm, "a depth below the stock top"));
    b.key("sigma_d_um", &B::sigma_d_um, plausible(0.0, 1000.0, "the process noise on the bar's deflection"));
    b.key("change_at_1", &B::change_at_1, int_range(0, 1'000'000));
    b.key("change_at_2", &B::change_at_2, int_range(0, 1'000'000));
  }
  {
    using N = NoiseParams;
    Section<N> n(rows, "noise", [](Scenario& s) -> N& { return s.noise; });
    n.key("seed", &N::seed);
    n.key("force_adc_v_rms", &N::force_adc_v_rms,
          plausible(0.0, 1.0, "noise at the force ADC's input (its 0-10 V range has a 2.4 mV LSB)"));
    n.key("accel_g_rms", &N::accel_g_rms,
          plausible(0.0, 1.0, "a MEMS accelerometer's noise over the tick bandwidth (mg class)"));
    n.key("accel_bias_g", &N::accel_bias_g, plausible(-1.0, 1.0, "an accelerometer's zero-g offset (tens of mg)"));
    n.key("dac_offset_v", &N::dac_offset_v,
          plausible(-1.0, 1.0, "a speed DAC's offset (mV class; 1 V is a tenth of full scale)"));
    n.key("dac_gain_error", &N::dac_gain_error, plausible(-0.1, 0.1, "a DAC's relative gain error (0.1-1 % class)"));
    n.key("encoder_glitch_per_s", &N::encoder_glitch_per_s,
          plausible(0.0, 1000.0, "miscounts per second (a thousand a second is a broken cable)"));
    n.key("encoder_glitch_counts", &N::encoder_glitch_counts, int_range(1, 1000));
    n.key("bore_gauge_um_rms", &N::bore_gauge_um_rms,
          plausible(0.0, 50.0, "a bore gauge's repeatability (um class; 50 um is a tenth of a millimetre band)"));
    n.key("bore_gauge_resolution_um", &N::bore_gauge_resolution_um,
          plausible(0.0, 100.0, "a bore gauge's reading step (0.1-10 um)"));
  }
  {
    using I = IoParams;
    Section<I> io(rows, "io", [](Scenario& s) -> I& { return s.io; });
    io.key("read_latency_us", &I::read_latency_us,
           plausible(0.0, 500.0, "a register transport's read after the latch (SPI or Ethernet: tens to hundreds of us)"));
    io.key("write_latency_us", &I::write_latency_us,
           plausible(0.0, 500.0, "a register transport's write (SPI or Ethernet: tens to hundreds of us)"));
    io.key("jitter_us", &I::jitter_us, plausible(0.0, 200.0, "a Linux board's transfer jitter (tens of us)"));
  }
  {
    using C = CircleParams;
    Section<C> c(rows, "circle", [](Scenario& s) -> C& { return s.circle; });
    c.key("radius_mm", &C::radius_mm, positive().plausible(1e-3, 500.0, "a circle the table's travel can hold"));
    c.key("feed_mm_s", &C::feed_mm_s, positive().plausible(1e-3, 1000.0, "a contouring feed up to 60 m/min"));
    c.key("ramp_s", &C::ramp_s, non_negative().plausible(0.0, 3600.0, "an hour at most"));
    c.key("dwell_s", &C::dwell_s, non_negative().plausible(0.0, 3600.0, "an hour at most"));
  }
  return rows;
}

}  // namespace

const std::vector<ScenarioKey>& scenario_keys() {
  static const std::vector<ScenarioKey> table = build_table();
  return table;
}

const ScenarioKey* find_scenario_key(std::string_view section, std::string_view name) {
  for (const ScenarioKey& key : scenario_keys()) {
    if (key.section == section && key.name == name) return &key;
  }
  return nullptr;
}

bool is_scenario_section(std::string_view path) {
  if (path.empty()) return false;
  for (const ScenarioKey& key : scenario_keys()) {
    const std::string_view section = key.section;
    if (section == path || (section.size() > path.size() && section.starts_with(path) && section[path.size()] == '.'))
      return true;
  }
  return false;
}

std::optional<double> scenario_key_number(const ScenarioKey& key, const Scenario& scenario) {
  // The target only locates the member; nothing here writes through it.
  const FieldTarget target = key.target(const_cast<Scenario&>(scenario));
  if (const auto* d = std::get_if<double*>(&target)) return **d;
  if (const auto* i = std::get_if<int*>(&target)) return static_cast<double>(**i);
  if (const auto* u = std::get_if<std::uint32_t*>(&target)) return static_cast<double>(**u);
  return std::nullopt;
}

}  // namespace tnv::emu
