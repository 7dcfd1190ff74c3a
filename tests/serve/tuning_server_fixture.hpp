#pragma once
// The tuning page's server on the emulated node, on a free loopback port,
// with an HTTP client that carries the secret as a script would (bearer
// token, the page's Origin on commands). Shared by the server's tests.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "tools/can_emu/node_connection.hpp"
#include "tools/serve/tuning_server.hpp"
// Last: <resolv.h>, which it includes, defines the macro _res that Eigen's headers use as a name.
#include <httplib.h>

namespace tnv::serve::testing {

namespace fs = std::filesystem;
const std::string kTabA = "tab-a-0123456789";
const std::string kTabB = "tab-b-0123456789";

inline fs::path temp_dir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("tnv_serve_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

class TuningServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_ / "chart.js");
    std::ofstream(dir_ / "chart.js" / "chart.min.js") << "// stand-in: the server only serves it\n";
    can_host::ConnectionOptions c;
    c.emu = true;
    c.emu_scenario = scenario();
    c.emu_storage = (dir_ / "node.params").string();
    std::vector<std::string> notes;
    connection_ = can_host::NodeConnection::open(c, notes);
    ServeOptions o;
    o.web_dir = TNV_SOURCE_DIR "/tools/serve/web";
    o.js_dir = dir_.string();
    o.info = {{"node", 1}};
    o.audit_path = (dir_ / "audit.jsonl").string();
    o.control_deadman = deadman();
    adjust(o);
    server_ = std::make_unique<TuningServer>(connection_->client(), connection_->emulated(), o);
    port_ = server_->start();
    listening_ = std::thread([this] { server_->listen(); });
    http_ = std::make_unique<httplib::Client>("127.0.0.1", port_);
    http_->set_read_timeout(30, 0);
    // A script's way in: the secret as a bearer token, the page's origin on commands.
    http_->set_default_headers({{"Authorization", "Bearer " + server_->secret()}, {"Origin", origin()}});
  }
  std::string origin() const { return "http://127.0.0.1:" + std::to_string(port_); }
  // Long here: a busy (sanitized) test machine must not lose control between two requests.
  virtual std::chrono::milliseconds deadman() const { return std::chrono::seconds(10); }
  virtual void adjust(ServeOptions&) const {}
  std::vector<nlohmann::json> audit_lines() const {
    std::vector<nlohmann::json> lines;
    std::ifstream in(dir_ / "audit.jsonl");
    for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
    return lines;
  }
  void TearDown() override {
    server_->stop();
    listening_.join();
    server_.reset();
    connection_.reset();
    fs::remove_all(dir_);
  }

  // The emulated table; the Bode test's is friction-free (with friction the
  // holding axis sticks and the loop is not the linear one the model is).
  virtual std::string scenario() const { return "no-cut"; }

  httplib::Result post(const std::string& path, const std::string& token, const nlohmann::json& body = {}) {
    return http_->Post(path.c_str(), {{"X-Tnv-Token", token}}, body.is_null() ? "" : body.dump(), "application/json");
  }
  nlohmann::json param(const std::string& name) {
    const httplib::Result r = http_->Get(("/api/params?filter=" + name).c_str());
    EXPECT_TRUE(r && r->status == 200);
    const nlohmann::json list = nlohmann::json::parse(r->body);
    for (const nlohmann::json& p : list["params"])
      if (p["name"] == name) return p;
    ADD_FAILURE() << "no parameter " << name << " in the list";
    return {};
  }
  static std::string error_of(const httplib::Result& r) { return nlohmann::json::parse(r->body).value("error", ""); }

  fs::path dir_;
  std::unique_ptr<can_host::NodeConnection> connection_;
  std::unique_ptr<TuningServer> server_;
  int port_ = 0;
  std::thread listening_;
  std::unique_ptr<httplib::Client> http_;
};

}  // namespace tnv::serve::testing
