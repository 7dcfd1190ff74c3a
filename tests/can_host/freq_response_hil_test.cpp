// Frequency response on the target (issue 17) over CAN on the emulated
// node: the plant measured on the reference table with friction off
// against the exact 1 ms ZOH model, the loop margins against the model of
// the loop the firmware runs, friction's effect reported, a bad band
// refused with the parameter named and nothing changed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "firmware/can/param_table.hpp"
#include "tests/sanitized_build.hpp"
#include "tools/can_emu/emulated_bus.hpp"
#include "tools/can/freq_response_run.hpp"
#include "tools/can/node_client.hpp"

namespace tnv::freq_response_hil_test {
namespace {

namespace can = fw::can;
using can_host::EmulatedBus;
using can_host::Micros;
using can_host::NodeClient;

constexpr const char* kNoFriction = TNV_SOURCE_DIR "/tests/data/tables/no-friction.toml";

struct FreqNode {
  std::unique_ptr<EmulatedBus> bus;
  std::unique_ptr<NodeClient> client;
  FreqNode() = default;
  FreqNode(FreqNode&&) = default;
  ~FreqNode() {
    if (bus) std::filesystem::remove(bus->storage_path());
  }
};

FreqNode freq_enabled_node(const std::string& scenario, const std::string& name) {
  can_host::EmulatedNodeOptions o;
  o.scenario = scenario;
  std::string file = "tnv_freq_";
  o.storage_path = (std::filesystem::temp_directory_path() / file.append(std::to_string(::getpid())).append(name)).string();
  std::filesystem::remove(o.storage_path);
  std::string error;
  FreqNode n;
  n.bus = EmulatedBus::create(o, error);
  EXPECT_TRUE(n.bus) << error;
  if (!n.bus) return n;
  n.client = std::make_unique<NodeClient>(*n.bus, n.bus->node_id());
  n.client->command(can::CommandCode::enable);
  n.client->pump(Micros{300'000});
  return n;
}

fw::AxisModel freq_table_zoh(const EmulatedBus& bus, hal::Axis axis) {
  const emu::AxisPlantParams& p = bus.scenario().plant[hal::index(axis)];
  return fw::zoh_axis_model(p.tau_s, p.gain, fw::kControlPeriod_s);
}

double freq_wrapped_deg(double deg) { return std::remainder(deg, 360.0); }

// Each axis is judged alone: a sanitizer build measures X only (the same code, half the CPU).
constexpr bool kXOnly = tnv::test::kSanitizedBuild;

TEST(FreqResponseHil, FrictionOffPlantMatchesTheExactZohModelFrom1To100Hz) {
  for (const hal::Axis axis : {hal::Axis::x, hal::Axis::y}) {
    if (kXOnly && axis != hal::Axis::x) continue;
    FreqNode n = freq_enabled_node(kNoFriction, axis == hal::Axis::x ? "plant_x" : "plant_y");
    ASSERT_TRUE(n.bus);
    can_host::FreqResponseOptions o;
    o.loop = tune::LoopKind::plant;
    o.plant_model = freq_table_zoh(*n.bus, axis);
    const can_host::FreqResponseResult r = can_host::run_freq_response(*n.client, axis, o);
    ASSERT_EQ(r.points.size(), o.tones);
    EXPECT_NEAR(r.points.front().freq_hz, 1.0, 1e-9);
    EXPECT_NEAR(r.points.back().freq_hz, 100.0, 1e-9);
    double worst_db = 0.0, worst_deg = 0.0;
    for (const can_host::FreqResponsePoint& p : r.points) {
      // The model here is computed from the scenario's tau, not from the measurement.
      const std::complex<double> zoh = tune::plant_response(freq_table_zoh(*n.bus, axis), p.freq_hz);
      worst_db = std::fmax(worst_db, std::fabs(tune::gain_db(p.measured) - tune::gain_db(zoh)));
      worst_deg = std::fmax(worst_deg, std::fabs(freq_wrapped_deg(tune::phase_deg(p.measured) - tune::phase_deg(zoh))));
      EXPECT_GE(p.coherence, 0.0);
      EXPECT_LE(p.coherence, 1.0);
    }
    const char* a = axis == hal::Axis::x ? "x" : "y";
    EXPECT_LT(worst_db, 1.0) << a << ": worst gain error 1..100 Hz, dB";
    EXPECT_LT(worst_deg, 5.0) << a << ": worst phase error 1..100 Hz, deg";
    EXPECT_GT(r.min_coherence, 0.99) << a << ": lowest coherence of the friction-free plant";
    ::testing::Test::RecordProperty(std::string(a) + "_worst_gain_error_db", std::to_string(worst_db));
    ::testing::Test::RecordProperty(std::string(a) + "_worst_phase_error_deg", std::to_string(worst_deg));
  }
}

// The margins of `kind`'s loop, measured with every closed-loop option at
// the controller's default (freq_response_defaults.hpp: every harmonic of
// 10 Hz from 10 to 450 Hz, riding on a carrier of about 3 mm/s, 10 for the
// PID, that decorrelates the encoder's quantisation from the excitation), within 5 %
// of the model's on both axes (docs/frequency-response.md).
void expect_default_margins_within_5_percent(fw::ControllerKind kind, const char* name) {
  for (const hal::Axis axis : {hal::Axis::x, hal::Axis::y}) {
    if (kXOnly && axis != hal::Axis::x) continue;
    const char* a = axis == hal::Axis::x ? "x" : "y";
    FreqNode n = freq_enabled_node(kNoFriction, std::string(name) + "_margins_" + a);
    ASSERT_TRUE(n.bus);
    n.client->command(can::CommandCode::select_controller, static_cast<std::uint8_t>(hal::index(axis)),
                      static_cast<std::uint8_t>(kind));
    const double x0_mm = n.bus->rig().task.last_record().axis[hal::index(axis)].reference_mm;
    can_host::FreqResponseOptions o;
    o.loop = tune::LoopKind::open;
    o.plant_model = freq_table_zoh(*n.bus, axis);
    const can_host::FreqResponseResult r = can_host::run_freq_response(*n.client, axis, o);
    ASSERT_EQ(r.controller, name) << a;
    ASSERT_EQ(r.points.size(), 45u) << a;
    EXPECT_GT(std::fabs(r.options.carrier_mm_s.value_or(0.0)), 2.5) << a << ": the default runs on a carrier";
    // The run puts the table back where it stood.
    // The move back's distance is an f32 on the wire: well under a count (0.42 um).
    EXPECT_NEAR(n.bus->rig().task.last_record().axis[hal::index(axis)].reference_mm, x0_mm, 1e-4) << a;
    ASSERT_TRUE(r.margins.crossover_found) << a;
    ASSERT_TRUE(r.model.margins.crossover_found) << a;
    EXPECT_NEAR(r.margins.crossover_hz, r.model.margins.crossover_hz, 0.05 * r.model.margins.crossover_hz)
        << a << ": crossover Hz, measured vs model";
    EXPECT_NEAR(r.margins.phase_margin_deg, r.model.margins.phase_margin_deg, 0.05 * r.model.margins.phase_margin_deg)
        << a << ": phase margin deg, measured vs model";
    ASSERT_TRUE(std::isfinite(r.margins.gain_margin_db)) << a << ": no phase crossover up to 450 Hz";
    ASSERT_TRUE(std::isfinite(r.model.margins.gain_margin_db)) << a << ": the model has no phase crossover";
    EXPECT_NEAR(r.margins.gain_margin_db, r.model.margins.gain_margin_db, 0.05 * r.model.margins.gain_margin_db)
        << a << ": gain margin dB, measured vs model";
    ::testing::Test::RecordProperty(std::string(a) + "_gain_margin_db", std::to_string(r.margins.gain_margin_db));
    ::testing::Test::RecordProperty(std::string(a) + "_phase_margin_deg", std::to_string(r.margins.phase_margin_deg));
    ::testing::Test::RecordProperty(std::string(a) + "_crossover_hz", std::to_string(r.margins.crossover_hz));
  }
}

TEST(FreqResponseHil, FrictionOffPidLoopMarginsWithin5PercentOfTheModelOnBothAxes) {
  expect_default_margins_within_5_percent(fw::ControllerKind::pid, "pid");
}

TEST(FreqResponseHil, FrictionOffRdvscLoopMarginsWithin5PercentOfTheModelOnBothAxes) {
  expect_default_margins_within_5_percent(fw::ControllerKind::rdvsc, "rdvsc");
}

TEST(FreqResponseHil, FrictionOnRunCompletesAndReportsItsCoherence) {
  FreqNode n = freq_enabled_node("no-cut", "friction");
  ASSERT_TRUE(n.bus);
  can_host::FreqResponseOptions o;
  o.loop = tune::LoopKind::plant;
  o.plant_model = freq_table_zoh(*n.bus, hal::Axis::x);
  const can_host::FreqResponseResult r = can_host::run_freq_response(*n.client, hal::Axis::x, o);
  ASSERT_EQ(r.points.size(), o.tones);
  double worst_db = 0.0;
  for (const can_host::FreqResponsePoint& p : r.points) {
    ASSERT_TRUE(std::isfinite(p.coherence));
    EXPECT_GE(p.coherence, 0.0);
    EXPECT_LE(p.coherence, 1.0);
    worst_db = std::fmax(worst_db, std::fabs(tune::gain_db(p.measured) - tune::gain_db(p.model)));
  }
  EXPECT_LE(r.min_coherence, 1.0);
  // Coulomb friction of 1.5 mm/s against a 10 mm/s multisine: the fit is off, by how much is reported.
  ::testing::Test::RecordProperty("friction_worst_gain_error_db", std::to_string(worst_db));
  ::testing::Test::RecordProperty("friction_min_coherence", std::to_string(r.min_coherence));
  EXPECT_TRUE(std::isfinite(worst_db));
}

TEST(FreqResponseHil, BadBandIsRefusedNamingTheParameterAndChangesNothing) {
  FreqNode n = freq_enabled_node(kNoFriction, "bad_band");
  ASSERT_TRUE(n.bus);
  const can::ParamDef& f_min = *can::find_param("excite.f_min_hz");
  const can::ParamDef& f_max = *can::find_param("excite.f_max_hz");
  const can::ParamDef& tones = *can::find_param("excite.tones");
  const double before[] = {n.client->get(f_min), n.client->get(f_max), n.client->get(tones)};
  n.client->stage(f_min, 50.0);
  n.client->stage(f_max, 20.0);
  try {
    n.client->commit();
    FAIL() << "f_min 50 Hz above f_max 20 Hz accepted";
  } catch (const can_host::RequestError& e) {
    EXPECT_EQ(e.code(), can::ErrorCode::invalid) << e.what();
    EXPECT_NE(std::string(e.what()).find("excite.f_max_hz"), std::string::npos) << e.what();
  }
  n.client->discard();
  n.client->stage(f_min, 10.0);
  n.client->stage(f_max, 50.0);
  n.client->stage(tones, 6.0);  // 10..50 Hz holds 5 harmonics of 10 Hz
  EXPECT_THROW(n.client->commit(), can_host::RequestError);
  n.client->discard();
  EXPECT_EQ(n.client->get(f_min), before[0]);
  EXPECT_EQ(n.client->get(f_max), before[1]);
  EXPECT_EQ(n.client->get(tones), before[2]);
  // A carrier that is not finite or beyond 20 mm/s: refused, naming it, nothing changed.
  const can::ParamDef& carrier = *can::find_param("excite.carrier_mm_s");
  const double carrier_before = n.client->get(carrier);
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), 25.0, -25.0}) {
    n.client->stage(f_min, 10.0);
    try {
      n.client->stage(carrier, bad);
      n.client->commit();
      FAIL() << "carrier " << bad << " accepted";
    } catch (const can_host::RequestError& e) {
      EXPECT_NE(std::string(e.what()).find("excite.carrier_mm_s"), std::string::npos) << e.what();
    }
    n.client->discard();
  }
  EXPECT_EQ(n.client->get(carrier), carrier_before);
  EXPECT_EQ(n.client->get(f_min), before[0]);
  // The host's own check names the option before anything is sent.
  can_host::FreqResponseOptions o;
  o.duration_s = 40.0;
  EXPECT_NE(can_host::check_options(o).find("duration_s"), std::string::npos) << can_host::check_options(o);
  EXPECT_THROW(can_host::run_freq_response(*n.client, hal::Axis::x, o), std::invalid_argument);
  o = {};
  o.carrier_mm_s = 25.0;
  EXPECT_NE(can_host::check_options(o).find("carrier_mm_s"), std::string::npos) << can_host::check_options(o);
  EXPECT_THROW(can_host::run_freq_response(*n.client, hal::Axis::x, o), std::invalid_argument);
  EXPECT_FALSE(n.bus->rig().task.exciting());
}

// A carrier whose travel would leave the soft limits ahead goes the other
// way, and the table ends where it stood.
TEST(FreqResponseHil, CarrierTurnsAroundAtTheSoftLimitAndTheTableReturns) {
  FreqNode n = freq_enabled_node(kNoFriction, "carrier_limit");
  ASSERT_TRUE(n.bus);
  // The table 5 mm short of the 250 mm soft limit.
  n.client->command(can::CommandCode::zero, 0, 0, 245.0);
  n.client->pump(Micros{20'000});
  const double x0_mm = n.bus->rig().task.last_record().axis[0].reference_mm;
  can_host::FreqResponseOptions o;
  o.loop = tune::LoopKind::open;
  o.duration_s = 4.0;  // 12 mm at 3 mm/s: only the negative way fits
  o.plant_model = freq_table_zoh(*n.bus, hal::Axis::x);
  const can_host::FreqResponseResult r = can_host::run_freq_response(*n.client, hal::Axis::x, o);
  EXPECT_LT(r.options.carrier_mm_s.value_or(0.0), -2.5);
  EXPECT_NEAR(n.bus->rig().task.last_record().axis[0].reference_mm, x0_mm, 1e-4);
  EXPECT_EQ(n.bus->rig().task.state(), fw::MotionState::holding);
  EXPECT_EQ(n.client->get(*can::find_param("excite.carrier_mm_s")), 0.0) << "restored";
}

}  // namespace
}  // namespace tnv::freq_response_hil_test
