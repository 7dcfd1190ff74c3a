#pragma once
// A campaign file (TOML, docs/campaigns.md): the experiment, controllers,
// a scenario, a run count, a master seed and [vary], distributions over
// scenario keys (docs/scenarios.md) and firmware parameters (tnvctl
// params list). Every key, name and distribution range is checked here,
// through the scenario loader and the parameter table themselves; an
// error is one line, "study.toml:9:1: vary.\"plant.x.gain\": ...", and no
// spec is returned.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "emulator/scenario.hpp"
#include "firmware/control/axis_controller.hpp"
#include "tools/campaign/sampling.hpp"

namespace tnv::campaign {

enum class DistributionKind { uniform, normal, lognormal, list };
const char* to_string(DistributionKind kind) noexcept;

struct VaryInput {
  std::string name;           // as written: "plant.x.coulomb_mm_s", "x.sliding.gamma"
  bool is_parameter = false;  // a firmware parameter, else a scenario key
  DistributionKind kind = DistributionKind::uniform;
  double a = 0.0;  // uniform: low; normal: mean; lognormal: median
  double b = 0.0;  // uniform: high; normal, lognormal: sigma (of the log for lognormal)
  nlohmann::ordered_json values = nlohmann::ordered_json::array();  // list: numbers, booleans or strings
  int line = 0;
  int column = 0;
};

struct CampaignSpec {
  std::string source;      // the file as named
  std::string experiment;  // "circle", "path", ... (experiment.hpp)
  std::vector<fw::ControllerKind> controllers;  // empty for an experiment without a controller choice
  std::string scenario;       // a built-in name, or the file as written
  std::string scenario_text;  // the file's text when it is a file ("" for a built-in)
  emu::Scenario base;
  std::size_t runs = 0;  // samples; each is run once per controller
  std::uint64_t seed = 0;
  Sampling sampling = Sampling::random;
  double limit_um = 5.0;  // the report's yield limit
  std::vector<VaryInput> vary;
  // The experiment's own keys (path's program, ...), every one present:
  // absent ones at their defaults.
  nlohmann::ordered_json settings = nlohmann::ordered_json::object();
  std::string program_text;  // path: the program file's text
};

struct CampaignResult {
  std::optional<CampaignSpec> spec;
  std::string error;
};

inline constexpr std::size_t kMaxCampaignRuns = 1'000'000;

// `base_dir`: where a scenario file named in the campaign is looked for.
CampaignResult parse_campaign_text(std::string_view text, std::string_view source_name,
                                   const std::filesystem::path& base_dir);
CampaignResult load_campaign_file(const std::string& path);

// The value drawn for `input` at the unit-interval point u.
nlohmann::ordered_json value_at(const VaryInput& input, double u);

}  // namespace tnv::campaign
