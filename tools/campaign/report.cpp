#include "tools/campaign/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>

#include <sqlite3.h>

#include "tools/campaign/experiment.hpp"
#include "tools/campaign/sqlite_handle.hpp"

namespace tnv::campaign {

using ojson = nlohmann::ordered_json;

double quantile_sorted(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double pos = q * static_cast<double>(sorted.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (sorted[hi] - sorted[lo]) * (pos - static_cast<double>(lo));
}

namespace {

std::vector<double> ranks(const std::vector<double>& v) {
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  std::vector<double> r(v.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
    const double average = (static_cast<double>(i) + static_cast<double>(j)) / 2.0 + 1.0;
    for (std::size_t k = i; k <= j; ++k) r[order[k]] = average;
    i = j + 1;
  }
  return r;
}

}  // namespace

double spearman(const std::vector<double>& x, const std::vector<double>& y) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (x.size() != y.size() || x.size() < 2) return nan;
  const std::vector<double> rx = ranks(x), ry = ranks(y);
  const double n = static_cast<double>(x.size());
  const double mean = (n + 1.0) / 2.0;
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (rx[i] - mean) * (ry[i] - mean);
    sxx += (rx[i] - mean) * (rx[i] - mean);
    syy += (ry[i] - mean) * (ry[i] - mean);
  }
  if (sxx == 0.0 || syy == 0.0) return nan;
  return sxy / std::sqrt(sxx * syy);
}

CampaignReport report_campaign(const std::filesystem::path& database, const std::string& metric,
                               std::optional<double> limit) {
  CampaignReport report;
  report.metric = metric;
  std::error_code ec;
  if (!std::filesystem::exists(database, ec)) {
    report.error = database.string() + ": missing (tnv-hil campaign merge DIR first)";
    return report;
  }
  SqliteDb db;
  if (sqlite3_open_v2(database.c_str(), &db.db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    report.error = database.string() + ": cannot open";
    return report;
  }
  const auto sql_error = [&] { return database.string() + ": " + sqlite3_errmsg(db.db); };
  // The campaign's limit and varied inputs.
  std::vector<std::string> inputs;
  {
    SqliteStatement s;
    if (sqlite3_prepare_v2(db.db, "SELECT key, value FROM campaign WHERE key IN ('limit_um', 'vary', 'experiment');", -1, &s.stmt,
                           nullptr) != SQLITE_OK) {
      report.error = sql_error();
      return report;
    }
    while (sqlite3_step(s.stmt) == SQLITE_ROW) {
      const std::string key = reinterpret_cast<const char*>(sqlite3_column_text(s.stmt, 0));
      if (key == "limit_um") report.limit = sqlite3_column_double(s.stmt, 1);
      if (key == "experiment" && report.metric.empty()) {
        const Experiment* e = find_experiment(reinterpret_cast<const char*>(sqlite3_column_text(s.stmt, 1)));
        if (e != nullptr) report.metric = e->default_metric;
      }
      if (key == "vary") {
        for (const auto& v : ojson::parse(reinterpret_cast<const char*>(sqlite3_column_text(s.stmt, 1))))
          inputs.push_back(v.at("name").get<std::string>());
      }
    }
  }
  if (limit) report.limit = *limit;
  if (report.metric.empty()) report.metric = "max_um";
  {
    SqliteStatement u;
    if (sqlite3_prepare_v2(db.db, "SELECT count(*) FROM runs WHERE io_work_unmetered != 0;", -1, &u.stmt, nullptr) !=
            SQLITE_OK ||
        sqlite3_step(u.stmt) != SQLITE_ROW) {
      report.error = sql_error();
      return report;
    }
    report.io_work_unmetered_runs = static_cast<std::size_t>(sqlite3_column_int64(u.stmt, 0));
  }
  std::string select = "SELECT controller, status, " + quoted_identifier(report.metric);
  for (const std::string& in : inputs) select += ", " + quoted_identifier(in);
  select += " FROM runs ORDER BY run_id;";
  SqliteStatement s;
  if (sqlite3_prepare_v2(db.db, select.c_str(), -1, &s.stmt, nullptr) != SQLITE_OK) {
    report.error = sql_error() + " (--metric: a result column such as max_um)";
    return report;
  }
  struct Columns {
    std::size_t runs = 0;
    std::vector<double> metric;
    std::vector<std::vector<double>> inputs;
  };
  std::vector<std::string> order;
  std::map<std::string, Columns> by_controller;
  while (sqlite3_step(s.stmt) == SQLITE_ROW) {
    const std::string controller = reinterpret_cast<const char*>(sqlite3_column_text(s.stmt, 0));
    const std::string status = reinterpret_cast<const char*>(sqlite3_column_text(s.stmt, 1));
    if (!by_controller.count(controller)) {
      order.push_back(controller);
      by_controller[controller].inputs.resize(inputs.size());
    }
    Columns& c = by_controller[controller];
    ++c.runs;
    if (status != "ok" || sqlite3_column_type(s.stmt, 2) == SQLITE_NULL) continue;
    c.metric.push_back(sqlite3_column_double(s.stmt, 2));
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      const int t = sqlite3_column_type(s.stmt, static_cast<int>(3 + i));
      c.inputs[i].push_back(t == SQLITE_INTEGER || t == SQLITE_FLOAT ? sqlite3_column_double(s.stmt, static_cast<int>(3 + i))
                                                                     : std::numeric_limits<double>::quiet_NaN());
    }
  }
  for (const std::string& name : order) {
    const Columns& c = by_controller[name];
    ControllerReport r;
    r.controller = name;
    r.runs = c.runs;
    r.ok = c.metric.size();
    r.within_limit = static_cast<std::size_t>(std::count_if(c.metric.begin(), c.metric.end(),
                                                            [&](double v) { return v <= report.limit; }));
    r.yield = r.runs == 0 ? 0.0 : static_cast<double>(r.within_limit) / static_cast<double>(r.runs);
    std::vector<double> sorted = c.metric;
    std::sort(sorted.begin(), sorted.end());
    r.p50 = quantile_sorted(sorted, 0.5);
    r.p90 = quantile_sorted(sorted, 0.9);
    r.p99 = quantile_sorted(sorted, 0.99);
    r.max = sorted.empty() ? std::numeric_limits<double>::quiet_NaN() : sorted.back();
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      const bool numeric = std::none_of(c.inputs[i].begin(), c.inputs[i].end(), [](double v) { return std::isnan(v); });
      r.sensitivity.push_back({inputs[i], numeric ? spearman(c.inputs[i], c.metric) : std::numeric_limits<double>::quiet_NaN()});
    }
    std::stable_sort(r.sensitivity.begin(), r.sensitivity.end(), [](const Sensitivity& a, const Sensitivity& b) {
      const double x = std::isnan(a.spearman) ? -1.0 : std::fabs(a.spearman);
      const double y = std::isnan(b.spearman) ? -1.0 : std::fabs(b.spearman);
      return x > y;
    });
    report.controllers.push_back(std::move(r));
  }
  if (report.controllers.empty()) report.error = database.string() + ": no runs";
  return report;
}

std::string report_text(const CampaignReport& report) {
  std::string out;
  char buf[256];
  if (report.io_work_unmetered_runs > 0) {
    std::snprintf(buf, sizeof buf,
                  "warning: %zu runs ran an [io] scenario on a build without the work meter (their output writes "
                  "landed sooner than on a metered build: docs/performance.md)\n",
                  report.io_work_unmetered_runs);
    out += buf;
  }
  for (const ControllerReport& r : report.controllers) {
    std::snprintf(buf, sizeof buf,
                  "%s: %zu runs, %zu finished; yield %.1f %% (%s <= %g); %s p50 %.3f  p90 %.3f  p99 %.3f  max %.3f\n",
                  r.controller.c_str(), r.runs, r.ok, 100.0 * r.yield, report.metric.c_str(), report.limit,
                  report.metric.c_str(), r.p50, r.p90, r.p99, r.max);
    out += buf;
    for (const Sensitivity& s : r.sensitivity) {
      if (std::isnan(s.spearman))
        std::snprintf(buf, sizeof buf, "  %-32s rho n/a\n", s.input.c_str());
      else
        std::snprintf(buf, sizeof buf, "  %-32s rho %+.3f\n", s.input.c_str(), s.spearman);
      out += buf;
    }
  }
  return out;
}

ojson report_json(const CampaignReport& report) {
  ojson j = {{"metric", report.metric},
             {"limit", report.limit},
             {"io_work_unmetered_runs", report.io_work_unmetered_runs},
             {"controllers", ojson::array()}};
  const auto number = [](double v) { return std::isnan(v) ? ojson() : ojson(v); };
  for (const ControllerReport& r : report.controllers) {
    ojson c = {{"controller", r.controller}, {"runs", r.runs}, {"finished", r.ok}, {"within_limit", r.within_limit},
               {"yield", r.yield}, {"p50", number(r.p50)}, {"p90", number(r.p90)}, {"p99", number(r.p99)},
               {"max", number(r.max)}, {"sensitivity", ojson::array()}};
    for (const Sensitivity& s : r.sensitivity) c["sensitivity"].push_back({{"input", s.input}, {"spearman", number(s.spearman)}});
    j["controllers"].push_back(c);
  }
  return j;
}

}  // namespace tnv::campaign
