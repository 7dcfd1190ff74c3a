#pragma once
// What a merged campaign says (DIR/campaign.sqlite): per controller, the
// yield against a limit (runs that did not finish count as out), the
// quantiles of a result among the runs that finished, and which varied
// input drives it (Spearman rank correlation, strongest first).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace tnv::campaign {

struct Sensitivity {
  std::string input;
  double spearman = 0.0;  // NaN when the input does not vary or is not a number
};

struct ControllerReport {
  std::string controller;
  std::size_t runs = 0;
  std::size_t ok = 0;
  std::size_t within_limit = 0;
  double yield = 0.0;  // within_limit / runs
  double p50 = 0.0, p90 = 0.0, p99 = 0.0, max = 0.0;
  std::vector<Sensitivity> sensitivity;  // by |rho|, largest first
};

struct CampaignReport {
  std::string error;
  std::string metric;
  double limit = 0.0;
  std::vector<ControllerReport> controllers;
  // Rows of [io] runs done by a build without the work meter: their
  // output writes landed sooner than a metered build's (merge.hpp).
  std::size_t io_work_unmetered_runs = 0;
};

// `metric`: a result column (max_um, true_tool_max_um, ...), "" for the
// experiment's default (experiment.hpp); `limit`:
// nullopt for the campaign file's limit_um.
CampaignReport report_campaign(const std::filesystem::path& database, const std::string& metric,
                               std::optional<double> limit);

std::string report_text(const CampaignReport& report);
nlohmann::ordered_json report_json(const CampaignReport& report);

// Quantile q of sorted values (linear between order statistics, as numpy's default).
double quantile_sorted(const std::vector<double>& sorted, double q);
// Spearman's rho with average ranks for ties; NaN if either side is constant.
double spearman(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace tnv::campaign
