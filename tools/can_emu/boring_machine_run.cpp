#include "tools/can_emu/boring_machine_run.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "emulator/boring_pass.hpp"
#include "emulator/cutting_at_tool.hpp"
#include "emulator/machine.hpp"
#include "firmware/adaptive/boring/bore_measurement.hpp"
#include "firmware/can/param_table.hpp"
#include "tools/can/boring_node_link.hpp"
#include "tools/can/program_run.hpp"
#include "tools/can_emu/emulated_bus.hpp"
#include "tools/hil/boring_pass_program.hpp"
#include "tools/score/boring_node_resolution.hpp"

namespace tnv::can_host {

emu::Scenario boring_machine_scenario(const hil::BoringRunRequest& r) {
  emu::Scenario s;
  s.name = "boring";
  s.stock.enabled = true;
  s.boring.enabled = true;
  s.boring.sigma_d_um = r.process_sigma_mm * 1000.0;
  s.boring.change_at_1 = !r.change_at.empty() ? r.change_at[0] : 0;
  s.boring.change_at_2 = r.change_at.size() > 1 ? r.change_at[1] : 0;
  s.noise.bore_gauge_um_rms = r.gauge_noise_mm_rms * 1000.0;
  s.noise.bore_gauge_resolution_um = r.gauge_resolution_mm * 1000.0;
  s.noise.seed = static_cast<std::uint32_t>(r.gauge_seed);
  return s;
}

std::string boring_machine_refusal(const hil::BoringRunRequest& r, const BoringMachineOptions& o) {
  if (const std::string error = hil::validate_boring_request(r); !error.empty()) return error;
  if (const std::string why = hil::node_planner_refusal(r.planner, r.positions_mm); !why.empty()) return why;
  const emu::Scenario s = boring_machine_scenario(r);
  const emu::BoringProcessConfig process = emu::boring_process_config(s);
  if (r.planner.target_deflection_mm != process.preset_deflection_mm)
    return "target_deflection_mm: the machine's bar is preset for d0 = 0.1165 mm";
  if (r.planner.force_angle_deg != process.force_angle_deg)
    return "force_angle_deg: the machine's gauge reads with phi = 60 deg";
  const hil::BoringPassGeometry g = hil::boring_pass_geometry(s, o.spindle_rpm);
  const double l1 = g.overhang_at_top_mm + g.top_depth_mm;
  const double l2 = g.overhang_at_top_mm + g.bottom_depth_mm;
  if (r.positions_mm.size() != 2 || std::fabs(r.positions_mm[0] - l1) > 1e-9 ||
      std::fabs(r.positions_mm[1] - l2) > 1e-9)
    return "positions_mm: on the machine the measuring overhangs are the gauge depths' (40 and 310 mm)";
  return hil::validate_boring_pass(g, s.z_axis.travel_bottom_mm);
}

namespace {

// The gauge's two readings and what the bar did along the pass, after one part's program.
struct CutPart {
  std::array<emu::GaugeDepthReading, emu::BoringPass::kGaugeDepths> gauge{};
  double min_error_mm = 0.0, max_error_mm = 0.0;
};

}  // namespace

hil::BoringRunResult run_boring_on_machine(const hil::BoringRunRequest& r, std::uint64_t seed,
                                           const BoringMachineOptions& o) {
  if (const std::string why = boring_machine_refusal(r, o); !why.empty()) throw std::invalid_argument(why);
  hil::BoringRunResult result;
  result.seed = seed;
  EmulatedNodeOptions options;
  options.scenario_value = boring_machine_scenario(r);
  if (o.drive_rpm_at_full_scale > 0.0) options.scenario_value->spindle.rpm_at_full_scale = o.drive_rpm_at_full_scale;
  options.seed = static_cast<int>(seed);
  std::string file = "tnv_hil_boring_machine_";
  file.append(std::to_string(::getpid()));
  options.storage_path = (std::filesystem::temp_directory_path() / file).string();  // read at start, never written
  std::string error;
  std::unique_ptr<EmulatedBus> bus = EmulatedBus::create(options, error);
  if (!bus) {
    result.error = "no emulated node: " + error;
    return result;
  }
  emu::Machine& machine = bus->rig().machine;
  emu::BoringPass& bar = *machine.boring_pass();
  if (o.on_step) bus->set_step_observer([&machine, &o] { o.on_step(machine); });
  const hil::BoringPassGeometry geometry = hil::boring_pass_geometry(bus->scenario(), o.spindle_rpm);
  NodeClient client(*bus, bus->node_id());
  if (o.at_speed_fraction > 0.0) {
    try {
      client.set(*fw::can::find_param("spindle.at_speed_fraction"), o.at_speed_fraction);
    } catch (const std::exception& e) {
      result.error = std::string("spindle.at_speed_fraction: ") + e.what();
      return result;
    }
  }
  BoringNodeLink planner(client);
  if (const std::string why = planner.start(r.planner, r.positions_mm); !why.empty()) {
    result.error = "planner not started: " + why;
    return result;
  }
  const double d0 = r.planner.target_deflection_mm;
  const double band_mm = r.planner.band_sigmas * r.band_sigma_mm;
  ProgramRunOptions run_options;
  run_options.telemetry_ms = 0;  // judged on the machine's truth, not on a path score
  for (int part = 1; part <= r.parts; ++part) {
    const std::vector<hil::BoringLinkInfeed> infeeds = planner.infeeds(error);
    if (infeeds.size() != 2) {
      result.error = "part " + std::to_string(part) + ": no infeeds: " + error;
      return result;
    }
    bar.begin_part(part);
    const bool along_depth = o.feed_per_rev && o.along_depth;
    const std::string program =
        along_depth ? hil::boring_pass_depth_gcode(geometry, infeeds[0].infeed_mm_rev, infeeds[1].infeed_mm_rev)
                    : hil::boring_pass_gcode(geometry, infeeds[0].infeed_mm_rev, infeeds[1].infeed_mm_rev);
    const std::vector<hil::BoringPassSegment> segments =
        hil::boring_pass_segments(geometry, infeeds[0].infeed_mm_rev, infeeds[1].infeed_mm_rev);
    run_options.before_wire = nullptr;
    run_options.expected_s = 0.0;
    if (along_depth) {
      // The line is at the smaller infeed at the slowest (the node's S(L) lies between the two): its whole
      // length at that, and 10 s for the rapids and the spindle's start and stop.
      const double s_min_mm_rev = std::min(infeeds[0].infeed_mm_rev, infeeds[1].infeed_mm_rev);
      const double feed_mm = hil::boring_pass_end_depth_mm(geometry) - hil::boring_pass_start_depth_mm(geometry);
      run_options.expected_s = 10.0 + feed_mm / (s_min_mm_rev * geometry.spindle_rpm / 60.0);
    }
    if (along_depth)
      run_options.before_wire = [&geometry](gcode::GcodeProgram& p) {
        if (const std::string why = hil::mark_feed_along_depth(p, geometry); !why.empty())
          throw ProgramInputError(why);
      };
    else if (o.feed_per_rev)
      run_options.before_wire = [&segments](gcode::GcodeProgram& p) {
        if (const std::string why = hil::mark_feed_per_rev(p, segments); !why.empty()) throw ProgramInputError(why);
      };
    try {
      const ProgramRunResult run = run_gcode(client, program, run_options);
      if (run.stream.end != StreamResult::End::done) {
        result.error = "part " + std::to_string(part) + ": the pass did not run to its end: " + run.stream.message;
        return result;
      }
    } catch (const std::exception& e) {
      result.error = "part " + std::to_string(part) + ": " + e.what();
      return result;
    }
    if (const std::uint64_t crashes = machine.cutting_at_tool()->crashes().count(); crashes > 0) {
      result.error = "part " + std::to_string(part) + ": the bar was in the stock with the spindle slow (" +
                     std::to_string(crashes) + " crashes)";
      return result;
    }
    const auto gauge = bar.read_gauge();
    hil::BoringPartRecord rec;
    rec.part = part;
    rec.true_c_mm = bar.process().c_mm(part);
    rec.true_alpha = bar.process().parameters(part).alpha;
    rec.true_beta = bar.process().parameters(part).beta;
    rec.pass_min_error_mm = bar.min_radius_error_mm();
    rec.pass_max_error_mm = bar.max_radius_error_mm();
    std::vector<double> readings;
    for (std::size_t i = 0; i < gauge.size(); ++i) {
      const emu::GaugeDepthReading& g = gauge[i];
      if (!g.cut) {
        result.error = "part " + std::to_string(part) + ": the bar did not pass gauge depth " +
                       std::to_string(g.depth_mm) + " mm feeding down";
        return result;
      }
      hil::BoringPositionRecord pos;
      pos.overhang_mm = r.positions_mm[i];
      pos.infeed_mm_rev = infeeds[i].infeed_mm_rev;
      pos.infeed_limited = infeeds[i].infeed_limited;
      pos.cut_infeed_mm_rev = g.infeed_mm_rev;
      pos.cut_overhang_mm = g.overhang_mm;
      pos.optimal_infeed_mm_rev = bar.process().optimal_infeed_mm_rev(part, pos.overhang_mm);
      pos.true_deflection_mm = bar.process().deflection_mm(part, g.infeed_mm_rev, g.overhang_mm);
      pos.measured_deflection_mm = fw::deflection_from_bore_error_mm(planner.received_reading_mm(g.reading_mm), d0,
                                                                     r.planner.force_angle_deg);
      readings.push_back(g.reading_mm);
      rec.positions.push_back(pos);
    }
    if (!hil::add_gauged_part(result, std::move(rec), planner.record(part, readings), d0, band_mm)) return result;
  }
  result.deflection_rms_mm = hil::deflection_rms_mm(result, d0);
  return result;
}

hil::BoringSweepResult run_boring_sweep_on_machine(const hil::BoringRunRequest& request, int seeds,
                                                   const BoringMachineOptions& options,
                                                   const hil::BoringProgress& progress, std::uint64_t first_seed) {
  if (const std::string why = boring_machine_refusal(request, options); !why.empty())
    throw std::invalid_argument(why);
  const hil::BoringSeedRun run_seed = [&](std::uint64_t seed) {
    return run_boring_on_machine(request, seed, options);
  };
  return hil::run_boring_sweep(request, seeds, "node over CAN, every part a boring pass on the emulated machine",
                               run_seed, progress, first_seed);
}

}  // namespace tnv::can_host
