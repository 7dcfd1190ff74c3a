#include "tools/campaign/manifest.hpp"

#include <fstream>
#include <system_error>
#include <unistd.h>

#include "emulator/scenario_file.hpp"
#include "emulator/text_file.hpp"
#include "tools/campaign/experiment.hpp"
#include "tools/campaign/sampling.hpp"

namespace tnv::campaign {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

std::uint64_t fnv1a64(std::string_view bytes) noexcept {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ull;
  }
  return h;
}

int run_seed(std::uint64_t master_seed, std::uint64_t sample) noexcept {
  return static_cast<int>(mix64(mix64(master_seed) ^ sample) >> 33);  // 0 .. 2^31 - 1
}

bool write_file_atomically(const fs::path& path, const std::string& text, std::string& error) {
  const fs::path tmp = path.string() + ".partial";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) {
      error = tmp.string() + ": cannot write";
      return false;
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    error = path.string() + ": " + ec.message();
    fs::remove(tmp, ec);
    return false;
  }
  return true;
}

std::optional<fw::ControllerKind> controller_from_string(std::string_view name) noexcept {
  for (const fw::ControllerKind k : {fw::ControllerKind::pid, fw::ControllerKind::dvsc, fw::ControllerKind::rdvsc})
    if (name == fw::to_string(k)) return k;
  return std::nullopt;
}

const char* controller_text(const std::optional<fw::ControllerKind>& controller) noexcept {
  return controller ? fw::to_string(*controller) : "none";
}

namespace {

std::string manifest_text(const CampaignSpec& spec, const std::vector<ManifestRun>& runs) {
  ojson head = ojson::object();
  head["format"] = kManifestFormat;
  head["source"] = fs::path(spec.source).filename().string();
  head["experiment"] = spec.experiment;
  head["scenario"] = spec.scenario_text.empty() ? spec.scenario : std::string(kScenarioCopyName);
  ojson controllers = ojson::array();
  for (const auto c : spec.controllers) controllers.push_back(fw::to_string(c));
  head["controllers"] = controllers;
  head["samples"] = spec.runs;
  head["seed"] = spec.seed;
  head["sampling"] = spec.sampling == Sampling::random ? "random" : "latin-hypercube";
  head["limit_um"] = spec.limit_um;
  if (!spec.settings.empty()) head["settings"] = spec.settings;
  ojson vary = ojson::array();
  for (const VaryInput& v : spec.vary) {
    ojson d = {{"name", v.name}, {"kind", v.is_parameter ? "parameter" : "scenario"}, {"distribution", to_string(v.kind)}};
    d["args"] = v.kind == DistributionKind::list ? v.values : ojson::array({v.a, v.b});
    vary.push_back(d);
  }
  head["vary"] = vary;
  std::string text = head.dump(2);
  text.resize(text.size() - 2);  // "\n}": "runs" follows, one run a line
  text += ",\n  \"runs\": [\n";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const ManifestRun& r = runs[i];
    ojson j = {{"run_id", r.run_id}, {"sample", r.sample}, {"controller", controller_text(r.controller)},
               {"seed", r.seed},     {"inputs", r.inputs}};
    text += "    " + j.dump() + (i + 1 < runs.size() ? ",\n" : "\n");
  }
  text += "  ]\n}\n";
  return text;
}

}  // namespace

PlanResult plan_campaign(const CampaignSpec& spec, const std::string& campaign_text, const fs::path& dir) {
  PlanResult result;
  std::vector<InputName> names;
  for (const VaryInput& v : spec.vary) names.push_back({v.name, v.is_parameter});
  const std::vector<double> u = unit_samples(spec.runs, spec.vary.size(), spec.seed, spec.sampling);
  std::vector<ManifestRun> runs;
  // An experiment without a controller choice runs each sample once.
  std::vector<std::optional<fw::ControllerKind>> controllers(spec.controllers.begin(), spec.controllers.end());
  if (controllers.empty()) controllers.emplace_back(std::nullopt);
  runs.reserve(spec.runs * controllers.size());
  for (std::size_t s = 0; s < spec.runs; ++s) {
    ojson inputs = ojson::object();
    for (std::size_t d = 0; d < spec.vary.size(); ++d)
      inputs[spec.vary[d].name] = value_at(spec.vary[d], u[s * spec.vary.size() + d]);
    const RunSetup setup = resolve_run_inputs(spec.base, names, inputs, spec.experiment);
    if (!setup.scenario) {
      const VaryInput* at = nullptr;
      for (const VaryInput& v : spec.vary)
        if (v.name == setup.bad_input) at = &v;
      result.error = spec.source + ":" + (at ? std::to_string(at->line) + ":" + std::to_string(at->column) : "1:1") +
                     ": " + (at ? "vary.\"" + at->name + "\": " : std::string()) + "sample " + std::to_string(s + 1) +
                     " (" + inputs.dump() + ") is outside the valid range: " + setup.error;
      return result;
    }
    for (const auto& controller : controllers) {
      ManifestRun r;
      r.run_id = runs.size() + 1;
      r.sample = s + 1;
      r.controller = controller;
      r.seed = run_seed(spec.seed, s + 1);
      r.inputs = inputs;
      runs.push_back(std::move(r));
    }
  }
  const std::string text = manifest_text(spec, runs);

  std::error_code ec;
  const fs::path manifest_path = dir / kManifestName;
  if (fs::exists(manifest_path, ec)) {
    std::string old, error;
    if (emu::read_text_file(manifest_path.string(), std::size_t{1} << 30, old, error) && old == text) {
      result.ok = true;  // planned before: the same campaign, nothing to do
      result.runs = runs.size();
      return result;
    }
    result.error = dir.string() + ": holds another campaign's manifest; plan into a new directory";
    return result;
  }
  if (fs::exists(dir, ec) && !fs::is_empty(dir, ec)) {
    result.error = dir.string() + ": not empty; plan into a new directory";
    return result;
  }
  fs::create_directories(dir / "shards", ec);
  if (ec) {
    result.error = dir.string() + ": " + ec.message();
    return result;
  }
  std::string error;
  if (!spec.scenario_text.empty() && !write_file_atomically(dir / kScenarioCopyName, spec.scenario_text, error)) {
    result.error = error;
    return result;
  }
  if (!spec.program_text.empty() && !write_file_atomically(dir / kProgramCopyName, spec.program_text, error)) {
    result.error = error;
    return result;
  }
  // The manifest last: a directory with a manifest is a whole plan.
  if (!write_file_atomically(dir / "campaign.toml", campaign_text, error) ||
      !write_file_atomically(manifest_path, text, error)) {
    result.error = error;
    return result;
  }
  result.ok = true;
  result.runs = runs.size();
  return result;
}

ManifestResult load_manifest(const fs::path& dir) {
  const fs::path path = dir / kManifestName;
  std::string text, error;
  if (!emu::read_text_file(path.string(), std::size_t{1} << 30, text, error))
    return {std::nullopt, emu::one_line(error) + " (plan the campaign first: tnv-hil campaign plan FILE --out DIR)"};
  Manifest m;
  try {
    const ojson j = ojson::parse(text);
    if (j.at("format") != kManifestFormat) return {std::nullopt, path.string() + ": not a " + kManifestFormat + " file"};
    m.experiment = j.at("experiment").get<std::string>();
    m.scenario = j.at("scenario").get<std::string>();
    m.limit_um = j.at("limit_um").get<double>();
    if (j.contains("settings")) m.settings = j.at("settings");
    for (const auto& v : j.at("vary")) m.inputs.push_back({v.at("name").get<std::string>(), v.at("kind") == "parameter"});
    for (const auto& r : j.at("runs")) {
      ManifestRun run;
      run.run_id = r.at("run_id").get<std::uint64_t>();
      run.sample = r.at("sample").get<std::uint64_t>();
      const std::string c = r.at("controller").get<std::string>();
      const std::optional<fw::ControllerKind> kind = controller_from_string(c);
      if (!kind && c != "none") return {std::nullopt, path.string() + ": unknown controller \"" + c + "\""};
      run.controller = kind;
      run.seed = r.at("seed").get<int>();
      run.inputs = r.at("inputs");
      if (run.run_id != m.runs.size() + 1) return {std::nullopt, path.string() + ": run ids out of order"};
      m.runs.push_back(std::move(run));
    }
  } catch (const std::exception& e) {
    return {std::nullopt, path.string() + ": " + emu::one_line(e.what())};
  }
  const Experiment* experiment = find_experiment(m.experiment);
  if (experiment == nullptr)
    return {std::nullopt, path.string() + ": experiment \"" + m.experiment + "\" is not one campaigns run"};
  for (const SettingKey& k : experiment->settings)
    if (!m.settings.contains(k.name)) return {std::nullopt, path.string() + ": settings." + k.name + " missing"};
  for (const ManifestRun& run : m.runs)
    if (run.controller.has_value() != (experiment->controllers != ControllerUse::none))
      return {std::nullopt, path.string() + ": run " + std::to_string(run.run_id) + ": controller does not fit " +
                                "experiment \"" + m.experiment + "\""};
  if (m.settings.contains("program")) {
    const fs::path program = dir / kProgramCopyName;
    if (!emu::read_text_file(program.string(), std::size_t{16} << 20, m.program_text, error))
      return {std::nullopt, emu::one_line(error)};
  }
  emu::ScenarioResult base = m.scenario == kScenarioCopyName ? emu::load_scenario_file((dir / kScenarioCopyName).string())
                                                             : emu::resolve_scenario(m.scenario);
  if (!base.scenario) return {std::nullopt, base.error};
  m.base = *base.scenario;
  m.fingerprint = fnv1a64(text);
  return {std::move(m), {}};
}

}  // namespace tnv::campaign
