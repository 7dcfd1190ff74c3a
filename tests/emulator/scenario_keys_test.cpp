// The table of scenario keys (emulator/scenario_keys.cpp) against what it
// stands for: every range refuses a value just outside it, naming its key,
// and takes its own bounds; every key has its line in docs/scenarios.md and
// every line there is a key; every member of the Scenario is a key's.
// Generated from the table: a new row is tested without a new test.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <regex>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "emulator/scenario_file.hpp"
#include "emulator/scenario_keys.hpp"
#include "emulator/scenario_validation.hpp"
#include "hal/axis.hpp"
#include "tests/emulator/aggregate_members.hpp"

namespace tnv::emu {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kTiny = std::numeric_limits<double>::min();  // the smallest normal double

double just_below(double x) { return std::nextafter(x, -kInf); }
double just_above(double x) { return std::nextafter(x, kInf); }

// The key's member, in a scenario of defaults (for its type).
FieldTarget default_target(const ScenarioKey& key) {
  static Scenario defaults;
  return key.target(defaults);
}

bool is_integer_key(const ScenarioKey& key) { return std::holds_alternative<int*>(default_target(key)); }

// Values the rule must refuse, each as close to its range as a value of the key's type gets.
std::vector<double> just_outside(const KeyRule& rule, bool integer) {
  using Sign = KeyRule::Sign;
  using Range = KeyRule::Range;
  std::vector<double> out;
  const auto below = [&](double x) { out.push_back(integer ? x - 1.0 : just_below(x)); };
  const auto above = [&](double x) { out.push_back(integer ? x + 1.0 : just_above(x)); };
  const auto not_a_number = [&] {
    if (!integer) out.push_back(kNan);
  };
  switch (rule.sign) {
    case Sign::any: break;
    case Sign::finite: out.insert(out.end(), {kNan, kInf, -kInf}); break;
    case Sign::positive: out.push_back(0.0); not_a_number(); break;
    case Sign::non_negative: out.push_back(integer ? -1.0 : -kTiny); not_a_number(); break;
    case Sign::below: out.push_back(rule.limit); out.push_back(integer ? -1.0 : -kTiny); not_a_number(); break;
    case Sign::positive_multiple_of_4: out.insert(out.end(), {0.0, 6.0, -4.0}); break;
  }
  switch (rule.range) {
    case Range::none:
    case Range::with_other_keys: break;
    case Range::plausible:
    case Range::inf_or_plausible:
    case Range::int_range:
      below(rule.low);
      above(rule.high);
      if (rule.range != Range::int_range) not_a_number();
      break;
    case Range::zero_or_plausible:
      if (!integer && rule.low > kTiny) below(rule.low);
      above(rule.high);
      out.push_back(-kTiny);
      not_a_number();
      break;
    case Range::at_least: below(rule.low); break;
    case Range::one_of:
      below(std::min(rule.low, rule.high));
      above(std::max(rule.low, rule.high));
      if (std::abs(rule.high - rule.low) > 1.0) out.push_back(std::midpoint(rule.low, rule.high));
      break;
  }
  return out;
}

// Values the rule's range (and its sign, each on its own) must take: the bounds themselves.
std::vector<double> range_bounds(const KeyRule& rule) {
  using Range = KeyRule::Range;
  switch (rule.range) {
    case Range::plausible:
    case Range::int_range:
    case Range::one_of: return {rule.low, rule.high};
    case Range::zero_or_plausible: return {0.0, rule.low, rule.high};
    case Range::inf_or_plausible: return {-kInf, rule.low, rule.high, kInf};
    case Range::at_least: return {rule.low};
    case Range::none:
    case Range::with_other_keys: return {};
  }
  return {};
}
std::vector<double> sign_bounds(const KeyRule& rule) {
  using Sign = KeyRule::Sign;
  switch (rule.sign) {
    case Sign::finite: return {-std::numeric_limits<double>::max(), 0.0, std::numeric_limits<double>::max()};
    case Sign::positive: return {kTiny};
    case Sign::non_negative: return {0.0};
    case Sign::below: return {0.0, just_below(rule.limit)};
    case Sign::positive_multiple_of_4: return {4.0};
    case Sign::any: return {};
  }
  return {};
}

std::string toml_number(double value, bool integer) {
  return integer ? std::to_string(static_cast<long long>(value)) : format_number(value);
}

TEST(ScenarioKeys, EveryRangeRefusesAValueJustOutsideItNamingItsKey) {
  int cases = 0;
  for (const ScenarioKey& key : scenario_keys()) {
    if (!key.rule.has_range()) continue;
    const bool integer = is_integer_key(key);
    for (const double value : just_outside(key.rule, integer)) {
      const std::string text = "[" + key.section + "]\n" + key.name + " = " + toml_number(value, integer) + "\n";
      const ScenarioResult r = parse_scenario_text(text, "scen.toml");
      EXPECT_FALSE(r.scenario) << text << "accepted";
      const std::string where = "scen.toml:2:1: " + key.path() + ": must be ";
      EXPECT_EQ(r.error.substr(0, where.size()), where) << text << r.error;
      EXPECT_NE(r.error.find("(got " + format_number(value) + ")"), std::string::npos) << r.error;
      ++cases;
    }
  }
  EXPECT_GT(cases, 300);  // the table's ~130 ranged keys, two or more values each
}

TEST(ScenarioKeys, EveryRangeTakesItsBounds) {
  for (const ScenarioKey& key : scenario_keys()) {
    KeyRule range_only = key.rule;
    range_only.sign = KeyRule::Sign::any;
    for (const double value : range_bounds(key.rule)) EXPECT_EQ(range_only.violation(value), std::nullopt) << key.path();
    KeyRule sign_only = key.rule;
    sign_only.range = KeyRule::Range::none;
    for (const double value : sign_bounds(key.rule)) EXPECT_EQ(sign_only.violation(value), std::nullopt) << key.path();
  }
}

TEST(ScenarioKeys, EveryNumberHasARangeOrIsCheckedWithOtherKeys) {
  const Scenario s;
  for (const ScenarioKey& key : scenario_keys()) {
    const bool number = scenario_key_number(key, s).has_value();
    const bool uint32 = std::holds_alternative<std::uint32_t*>(default_target(key));
    if (!number || uint32) continue;  // the reader holds a uint32 to its type's range
    EXPECT_TRUE(key.rule.has_range() || key.rule.range == KeyRule::Range::with_other_keys) << key.path();
  }
}

TEST(ScenarioKeys, EachKeyOnceAndEachMemberOnce) {
  Scenario s;
  std::set<std::string> paths;
  std::set<const void*> members;
  for (const ScenarioKey& key : scenario_keys()) {
    EXPECT_TRUE(paths.insert(key.path()).second) << key.path() << " twice";
    const void* member = std::visit([](auto* p) { return static_cast<const void*>(p); }, key.target(s));
    EXPECT_TRUE(members.insert(member).second) << key.path() << " sets a member another key sets";
    EXPECT_EQ(find_scenario_key(key.section, key.name), &key);
  }
}

TEST(ScenarioKeys, TheDefaultsAreInsideEveryRange) {
  EXPECT_EQ(validate_scenario(Scenario{}), "");
}

TEST(ScenarioKeys, PerAxisKeysFollowTheAxisList) {
  for (const hal::Axis axis : hal::kAxes) {
    const std::string n = hal::axis_label(axis);
    EXPECT_NE(find_scenario_key("plant." + n, "tau_s"), nullptr) << n;
    EXPECT_NE(find_scenario_key("encoder", "offset_counts_" + n), nullptr) << n;
    EXPECT_NE(find_scenario_key("board", "home_" + n + "_mm"), nullptr) << n;
    EXPECT_NE(find_scenario_key("board", "power_up_offset_" + n + "_mm"), nullptr) << n;
  }
}

// --- docs/scenarios.md -------------------------------------------------------

// (section, key) of every `key = value` line in the doc's ```toml blocks, by
// the [section] header above it; a header line may name more sections in its
// comment ("[plant.x]  # and [plant.y]"). [[array]] tables are not keys of
// the table ([[fault]]: fault_schedule_file_test.cpp).
std::set<std::pair<std::string, std::string>> documented_keys() {
  std::ifstream in(std::string(TNV_SOURCE_DIR) + "/docs/scenarios.md");
  EXPECT_TRUE(in) << "docs/scenarios.md";
  std::set<std::pair<std::string, std::string>> keys;
  const std::regex header(R"(^\[([a-z0-9_.]+)\])");
  const std::regex more_sections(R"(\[([a-z0-9_.]+)\])");
  const std::regex key_line(R"(^([a-z0-9_]+) *=)");
  bool in_toml = false;
  std::vector<std::string> sections{""};
  std::string line;
  while (std::getline(in, line)) {
    if (line.starts_with("```")) {
      in_toml = line == "```toml";
      sections = {""};
      continue;
    }
    if (!in_toml) continue;
    std::smatch m;
    if (line.starts_with("[[")) {
      sections.clear();
    } else if (std::regex_search(line, m, header)) {
      sections.clear();
      for (auto it = std::sregex_iterator(line.begin(), line.end(), more_sections); it != std::sregex_iterator(); ++it)
        sections.push_back((*it)[1]);
    } else if (std::regex_search(line, m, key_line)) {
      for (const std::string& section : sections) keys.insert({section, m[1]});
    }
  }
  return keys;
}

TEST(ScenarioKeys, EveryKeyHasItsLineInTheDoc) {
  const auto documented = documented_keys();
  for (const ScenarioKey& key : scenario_keys()) {
    EXPECT_TRUE(documented.count({key.section, key.name}))
        << key.path() << ": no `" << key.name << " = ...` line under [" << key.section
        << "] in docs/scenarios.md's key block";
  }
}

TEST(ScenarioKeys, EveryKeyInTheDocIsAKey) {
  const auto documented = documented_keys();
  EXPECT_GT(documented.size(), 100u);
  for (const auto& [section, name] : documented)
    EXPECT_NE(find_scenario_key(section, name), nullptr) << section << "." << name << " is in docs/scenarios.md only";
}

// --- every member of the Scenario is reachable from the table -----------------

template <class T>
struct IsStdArray : std::false_type {};
template <class T, std::size_t N>
struct IsStdArray<std::array<T, N>> : std::true_type {};

// leaf(address, path) for every value a key could set, walking structs and arrays.
template <class T, class Leaf>
void visit_values(T& value, const std::string& path, Leaf& leaf) {
  if constexpr (std::is_same_v<T, double> || std::is_same_v<T, int> || std::is_same_v<T, bool> ||
                std::is_same_v<T, std::uint32_t> || std::is_same_v<T, std::string>) {
    leaf(static_cast<const void*>(&value), path);
  } else if constexpr (IsStdArray<T>::value) {
    for (std::size_t i = 0; i < value.size(); ++i) visit_values(value[i], path + "[" + std::to_string(i) + "]", leaf);
  } else if constexpr (std::is_same_v<T, std::vector<FaultSpec>>) {
    // [[fault]]: read beside the table (fault_schedule_file_test.cpp covers every kind's keys)
  } else if constexpr (std::is_same_v<T, std::vector<StockHole>>) {
    // [[stock.hole]]: read beside the table (stock_surface_test.cpp covers its keys)
  } else if constexpr (std::is_class_v<T> && std::is_aggregate_v<T>) {
    std::size_t i = 0;
    ::tnv::test::for_each_member(value, [&](auto& member) { visit_values(member, path + "." + std::to_string(i++), leaf); });
  } else {
    static_assert(sizeof(T) == 0, "a Scenario member of a type no scenario key holds: give the reader that type");
  }
}

TEST(ScenarioKeys, EveryMemberOfTheScenarioHasAKey) {
  Scenario s;
  std::map<const void*, std::string> targets;
  for (const ScenarioKey& key : scenario_keys())
    targets[std::visit([](auto* p) { return static_cast<const void*>(p); }, key.target(s))] = key.path();

  std::set<const void*> seen;
  auto leaf = [&](const void* address, const std::string& path) {
    seen.insert(address);
    EXPECT_TRUE(targets.count(address))
        << "Scenario member " << path << " (member indices from the top) is no key's: add its row to "
           "emulator/scenario_keys.cpp";
  };
  visit_values(s, "s", leaf);
  // The walk is complete: it found every member the table sets.
  for (const auto& [address, path] : targets) EXPECT_TRUE(seen.count(address)) << path << " not found by the walk";
}

// Each key, alone in a file with a value other than its default, reads
// back to that value: the reader sets the member the row names.
TEST(ScenarioKeys, EachKeyReadsBackFromAFile) {
  const Scenario defaults;
  for (const ScenarioKey& key : scenario_keys()) {
    const FieldTarget target = default_target(key);
    std::vector<std::string> values;
    if (const auto* b = std::get_if<bool*>(&target)) {
      values = {**b ? "false" : "true"};
    } else if (std::holds_alternative<std::string*>(target)) {
      values = {"\"every key\""};
    } else if (std::holds_alternative<std::uint32_t*>(target)) {
      values = {"4000000000"};
    } else {
      // Inside the key's own range: its bounds, or a step from the default;
      // the first one the rules between keys also take.
      const bool integer = std::holds_alternative<int*>(target);
      const double now = *scenario_key_number(key, defaults);
      std::vector<double> candidates;
      for (const double bound : range_bounds(key.rule))
        if (std::isfinite(bound)) candidates.push_back(bound);
      candidates.insert(candidates.end(), {now + 4.0, now - 4.0, now * 1.25, now * 0.75, now + 0.5, now - 0.5});
      for (const double c : candidates) {
        if (c != now && !(integer && c != std::floor(c)) && !key.rule.violation(c)) values.push_back(toml_number(c, integer));
      }
    }
    bool read_back = false;
    for (const std::string& value : values) {
      // A key that only makes sense with another one (the check between keys refuses it alone).
      const std::string prerequisite = key.section == "boring" && key.name == "enabled" ? "[stock]\nenabled = true\n" : "";
      const std::string text =
          prerequisite + (key.section.empty() ? "" : "[" + key.section + "]\n") + key.name + " = " + value + "\n";
      const ScenarioResult r = parse_scenario_text(text, "one.toml");
      if (!r.scenario) continue;
      const FieldTarget read = key.target(const_cast<Scenario&>(*r.scenario));
      const FieldTarget before = default_target(key);
      std::visit(
          [&](auto* got) {
            using T = std::remove_pointer_t<decltype(got)>;
            EXPECT_NE(*got, *std::get<T*>(before)) << text << "left the default";
            if constexpr (std::is_same_v<T, std::string>) {
              EXPECT_EQ(*got, "every key");
            } else if constexpr (std::is_same_v<T, bool>) {
              EXPECT_EQ(*got, value == "true");
            } else {
              EXPECT_EQ(toml_number(static_cast<double>(*got), !std::is_same_v<T, double>), value) << text;
            }
          },
          read);
      read_back = true;
      break;
    }
    EXPECT_TRUE(read_back) << key.path() << ": no value other than the default is accepted";
  }
}

}  // namespace
}  // namespace tnv::emu
