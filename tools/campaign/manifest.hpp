#pragma once
// A planned campaign on disk (DIR/manifest.json): every run's resolved
// inputs, controller and seed. Runs, replays and the merge read only this
// (and DIR/scenario.toml, the copied scenario file), never the campaign
// file again, so a run is the same whatever happens to that file.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "emulator/scenario.hpp"
#include "firmware/control/axis_controller.hpp"
#include "tools/campaign/campaign_file.hpp"
#include "tools/campaign/run_inputs.hpp"

namespace tnv::campaign {

inline constexpr const char* kManifestFormat = "tnv-campaign-manifest 1";
inline constexpr const char* kManifestName = "manifest.json";
inline constexpr const char* kScenarioCopyName = "scenario.toml";
inline constexpr const char* kProgramCopyName = "program.ngc";  // path's program

struct ManifestRun {
  std::uint64_t run_id = 0;  // from 1
  std::uint64_t sample = 0;  // from 1; a sample's runs differ only in the controller
  // None for an experiment without axis loops (boring): "none" on disk.
  std::optional<fw::ControllerKind> controller = fw::ControllerKind::rdvsc;
  int seed = 0;  // the run's seed (tools/hil/seeded_scenario.hpp), from the master seed and the sample
  nlohmann::ordered_json inputs;  // name -> value, in the file's [vary] order
};

struct Manifest {
  std::string experiment;
  std::string scenario;  // a built-in name, or kScenarioCopyName
  emu::Scenario base;
  std::vector<InputName> inputs;
  nlohmann::ordered_json settings = nlohmann::ordered_json::object();  // the experiment's own keys
  std::string program_text;  // path: the program (DIR/program.ngc)
  double limit_um = 5.0;
  std::vector<ManifestRun> runs;  // by run_id
  std::uint64_t fingerprint = 0;  // FNV-1a 64 of manifest.json's bytes: which campaign a shard belongs to
};

// The seed of sample `sample` (from 1) of a campaign with master seed `seed`.
int run_seed(std::uint64_t master_seed, std::uint64_t sample) noexcept;

// Every run resolved and checked (resolve_run_inputs), then the manifest
// and the campaign file (and scenario file) copied into `dir`; an error
// names the campaign file, the line and the input, and nothing is written.
// Planning the same file into the same directory again changes nothing;
// a directory holding anything else is refused.
struct PlanResult {
  bool ok = false;
  std::string error;
  std::size_t runs = 0;
};
PlanResult plan_campaign(const CampaignSpec& spec, const std::string& campaign_text, const std::filesystem::path& dir);

struct ManifestResult {
  std::optional<Manifest> manifest;
  std::string error;
};
ManifestResult load_manifest(const std::filesystem::path& dir);

std::optional<fw::ControllerKind> controller_from_string(std::string_view name) noexcept;
// "pid", "dvsc", "rdvsc", or "none".
const char* controller_text(const std::optional<fw::ControllerKind>& controller) noexcept;

std::uint64_t fnv1a64(std::string_view bytes) noexcept;

// Writes `text` to `path` through a temporary file renamed over it.
bool write_file_atomically(const std::filesystem::path& path, const std::string& text, std::string& error);

}  // namespace tnv::campaign
