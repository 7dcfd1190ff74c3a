// The checked-in DBC and protocol document are what the table generates.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "firmware/can/can_id.hpp"
#include "firmware/can/param_table.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "firmware/can/protocol_messages.hpp"
#include "hal/axis.hpp"
#include "tools/protogen/dbc_writer.hpp"
#include "tools/protogen/protocol_doc_writer.hpp"

namespace {

std::string read_source_file(const std::string& relative) {
  std::ifstream f(std::string(TNV_SOURCE_DIR) + "/" + relative, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// First differing line, for a failure message a person can act on.
std::string first_difference(const std::string& a, const std::string& b) {
  std::istringstream sa(a);
  std::istringstream sb(b);
  std::string la;
  std::string lb;
  for (int line = 1;; ++line) {
    const bool ga = static_cast<bool>(std::getline(sa, la));
    const bool gb = static_cast<bool>(std::getline(sb, lb));
    if (!ga && !gb) return "identical";
    if (!ga || !gb || la != lb) {
      std::string msg = "line ";
      msg += std::to_string(line);
      msg += ":\n  checked in: ";
      msg += ga ? la : "<end>";
      msg += "\n  generated:  ";
      msg += gb ? lb : "<end>";
      return msg;
    }
  }
}

constexpr const char* kHowToFix = "\nRegenerate: cmake --build build/release --target update-protocol-docs";

TEST(GeneratedDocs, DbcIsUpToDate) {
  const std::string checked_in = read_source_file("docs/tnv.dbc");
  ASSERT_FALSE(checked_in.empty()) << "docs/tnv.dbc is missing";
  const std::string generated = tnv::protogen::write_dbc(1);
  EXPECT_TRUE(checked_in == generated) << "docs/tnv.dbc is stale: " << first_difference(checked_in, generated)
                                       << kHowToFix;
}

TEST(GeneratedDocs, ProtocolDocIsUpToDate) {
  const std::string checked_in = read_source_file("docs/can-protocol.md");
  ASSERT_FALSE(checked_in.empty()) << "docs/can-protocol.md is missing";
  const std::string generated = tnv::protogen::write_protocol_doc();
  EXPECT_TRUE(checked_in == generated) << "docs/can-protocol.md is stale: " << first_difference(checked_in, generated)
                                       << kHowToFix;
}

// Every message appears in the DBC with its identifier, DLC and one SG_ per
// field, plus one multiplexed signal per parameter in PARAM_REQUEST and
// PARAM_REPLY and one 1-bit signal per heartbeat bit.
TEST(GeneratedDocs, DbcHasEveryMessageAndSignal) {
  for (std::uint8_t node : {std::uint8_t{1}, std::uint8_t{42}}) {
    const std::string dbc = tnv::protogen::write_dbc(node);
    for (const auto& m : tnv::fw::can::kMessages) {
      std::string name = m.name;
      for (char& c : name) c = static_cast<char>(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c);
      std::string bo = "BO_ ";
      bo += std::to_string(tnv::fw::can::make_can_id(m.id, node));
      bo += ' ';
      bo += name;
      bo += ": ";
      bo += std::to_string(m.dlc);
      const std::size_t at = dbc.find(bo);
      ASSERT_NE(at, std::string::npos) << "missing: " << bo;
      const std::size_t end = dbc.find("\n\n", at);
      const std::string block = dbc.substr(at, end - at);
      std::size_t signals = 0;
      for (std::size_t p = block.find(" SG_ "); p != std::string::npos; p = block.find(" SG_ ", p + 1)) ++signals;
      const std::string_view message(m.name);
      const bool param_message = message == "param_request" || message == "param_reply";
      std::size_t expected = m.fields.size();
      if (param_message) expected += tnv::fw::can::param_table().size();
      // The errors bits, and homed_<axis> and shaper_<axis> of the axes byte.
      if (message == "heartbeat") expected += std::size(tnv::fw::can::kHeartbeatBits) + 2 * tnv::hal::kAxisCount;
      EXPECT_EQ(signals, expected) << m.name;
      if (param_message) {
        EXPECT_NE(block.find(" SG_ param M : 16|16@1+"), std::string::npos) << "param multiplexes: " << m.name;
        const auto& gamma = *tnv::fw::can::find_param("x.sliding.gamma");
        EXPECT_NE(block.find(" SG_ x_sliding_gamma m" + std::to_string(gamma.id) + " : 32|32@1- (1,0) [0|1] \"\""),
                  std::string::npos)
            << block.substr(0, 400);
        const std::string id = std::to_string(tnv::fw::can::make_can_id(m.id, node));
        EXPECT_NE(dbc.find("SIG_VALTYPE_ " + id + " x_sliding_gamma : 1;"), std::string::npos) << "a float";
        EXPECT_NE(dbc.find("VAL_ " + id + " x_controller 0 \"pid\" 1 \"dvsc\" 2 \"rdvsc\" ;"), std::string::npos);
      }
      if (message == "heartbeat") {
        EXPECT_NE(block.find(" SG_ params_unsaved : 17|1@1+ (1,0) [0|1]"), std::string::npos) << block;
        const std::string id = std::to_string(tnv::fw::can::make_can_id(m.id, node));
        EXPECT_NE(dbc.find("BA_ \"GenMsgCycleTime\" BO_ " + id + " 100;"), std::string::npos) << "tlm.heartbeat_ms";
      }
    }
  }
}

}  // namespace
