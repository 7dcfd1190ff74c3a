#include "tools/tnvctl/session.hpp"

#include <cstdio>
#include <iostream>
#include <vector>

namespace tnv::tnvctl {

void Report::line(const std::string& text) const {
  if (json_) return;
  std::ostream& out = summary_on_stderr_ ? std::cerr : std::cout;  // stdout kept for the CSV rows
  out << text << '\n';
  out.flush();
}

void Session::open() {
  can_host::ConnectionOptions c;
  c.iface = options_.iface;
  c.emu = options_.emu;
  c.node = options_.node;
  c.host_id = options_.host_id;
  c.timeout_ms = options_.timeout_ms;
  c.emu_scenario = options_.emu_scenario;
  c.emu_seed = options_.emu_seed;
  c.emu_storage = options_.emu_storage;
  c.trace = options_.trace;
  std::vector<std::string> notes;
  try {
    connection_ = can_host::NodeConnection::open(c, notes);
  } catch (const can_host::ConnectionInputError& e) {
    throw BadInput(e.what());
  }
  for (const std::string& note : notes) std::fprintf(stderr, "tnvctl: %s\n", note.c_str());
}

can_host::NodeClient& Session::client() {
  if (!connection_) open();
  return connection_->client();
}

void Session::end() noexcept {
  if (!connection_) return;
  if (const std::string error = connection_->release_ownership(); !error.empty())
    std::fprintf(stderr, "tnvctl: could not release command ownership: %s\n", error.c_str());
}

can_host::EmulatedBus* Session::emulated() {
  client();
  return connection_->emulated();
}

}  // namespace tnv::tnvctl
