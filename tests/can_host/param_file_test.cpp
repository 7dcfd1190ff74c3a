// A node's parameter set as a TOML file: what export writes, import reads
// back exactly, and every kind of bad file refused with its line.
#include <gtest/gtest.h>

#include "tools/can/param_file.hpp"
#include "tools/can/param_text.hpp"

namespace tnv {
namespace {

namespace can = fw::can;
using can_host::ParamValue;

std::vector<ParamValue> writable_defaults() {
  const can::NodeSettings s = can::default_node_settings();
  std::vector<ParamValue> values;
  for (const can::ParamDef& p : can::param_table())
    if (p.access == can::Access::read_write) values.push_back({&p, p.get(s)});
  return values;
}

can_host::NodeIdentity identity() { return {3, 100, 0x1a2b3c4du}; }

std::string exported(const std::vector<ParamValue>& values) {
  return can_host::write_param_file(1, identity(), "2026-11-26T03:40:00Z", values);
}

std::string refusal(const std::string& text) {
  std::string error;
  EXPECT_FALSE(can_host::read_param_file(text, error).has_value()) << text;
  return error;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

TEST(ParamFile, EveryWritableParameterRoundTripsExactlyWithItsHeader) {
  std::vector<ParamValue> values = writable_defaults();
  // Something off the defaults of each kind: a float, an enumeration.
  for (ParamValue& v : values) {
    if (std::string_view(v.param->name) == "x.sliding.gamma") v.value = 0.3125;
    if (std::string_view(v.param->name) == "y.controller") v.value = 0;  // pid
  }
  std::string error;
  const auto file = can_host::read_param_file(exported(values), error);
  ASSERT_TRUE(file.has_value()) << error;
  EXPECT_EQ(file->node_id, 1u);
  EXPECT_EQ(file->identity.firmware_version, 100u);
  EXPECT_EQ(file->identity.build_id, 0x1a2b3c4du);
  EXPECT_EQ(file->identity.protocol_version, 3u);
  EXPECT_EQ(file->exported_utc, "2026-11-26T03:40:00Z");
  EXPECT_TRUE(file->hash_matches);
  ASSERT_EQ(file->params.size(), values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    EXPECT_EQ(file->params[i].param, values[i].param);
    EXPECT_EQ(can::to_wire(*values[i].param, file->params[i].value), can::to_wire(*values[i].param, values[i].value))
        << values[i].param->name;
  }
}

TEST(ParamFile, AnEditedValueBreaksTheHashButStillReads) {
  const std::vector<ParamValue> values = writable_defaults();
  const std::string text = exported(values);
  // Rewrite gamma's line, whatever its default.
  const auto at = text.find("\nx.sliding.gamma = ");
  ASSERT_NE(at, std::string::npos);
  const auto end = text.find('\n', at + 1);
  const std::string edited = text.substr(0, at + 1) + "x.sliding.gamma = 0.4375" + text.substr(end);
  std::string error;
  const auto file = can_host::read_param_file(edited, error);
  ASSERT_TRUE(file.has_value()) << error;
  EXPECT_FALSE(file->hash_matches);
  // Re-formatting alone (spacing, comments) keeps the hash.
  const auto same = can_host::read_param_file(replaced(text, "\nx.sliding.gamma = ", "\nx.sliding.gamma    =   "), error);
  ASSERT_TRUE(same.has_value()) << error;
  EXPECT_TRUE(same->hash_matches);
}

TEST(ParamFile, BadFilesAreRefusedNamingTheLineAndKey) {
  const std::string good = exported(writable_defaults());
  EXPECT_NE(refusal("this is = = not toml").find("not TOML"), std::string::npos);
  EXPECT_NE(refusal("[params]\nx.sliding.gamma = 0.25\n").find("needs a [node] and a [params]"), std::string::npos);
  EXPECT_NE(refusal(good + "[extra]\na = 1\n").find("extra: unknown table"), std::string::npos);
  std::string e = refusal(replaced(good, "\nx.sliding.gamma = ", "\nx.sliding.gama = "));
  EXPECT_NE(e.find("params.x.sliding.gama: no such parameter (did you mean x.sliding.gamma?)"), std::string::npos) << e;
  EXPECT_EQ(e.rfind("line ", 0), 0u) << e;
  e = refusal(good + "sys.protocol_version = 3\n");
  EXPECT_NE(e.find("read-only"), std::string::npos) << e;
  e = refusal(good + "\"x.sliding.gamma\" = 0.25\n");  // the same parameter as a quoted key
  EXPECT_NE(e.find("given twice"), std::string::npos) << e;
  e = refusal(replaced(good, "\nx.sliding.gamma = ", "\nx.sliding.gamma = [1, 2] #"));
  EXPECT_NE(e.find("expected a number"), std::string::npos) << e;
  e = refusal(replaced(good, "\nx.sliding.gamma = ", "\nx.sliding.gamma = 1e9 #"));
  EXPECT_NE(e.find("x.sliding.gamma"), std::string::npos) << e;
  e = refusal(replaced(good, "\nx.sliding.gamma = ", "\nx.sliding.gamma = nan #"));
  EXPECT_NE(e.find("x.sliding.gamma"), std::string::npos) << e;
  e = refusal(replaced(good, "id = 1\n", "id = 99\n"));
  EXPECT_NE(e.find("id (1..31"), std::string::npos) << e;
  e = refusal(replaced(good, "build_id = \"1a2b3c4d\"", "build_id = \"xyz\""));
  EXPECT_NE(e.find("build_id"), std::string::npos) << e;
  const std::string header_only = good.substr(0, good.find("[params]")) + "[params]\n";
  EXPECT_NE(refusal(header_only).find("empty"), std::string::npos);
}

}  // namespace
}  // namespace tnv
