// tnvctl serve: the live tuning page (tools/serve) for the node this
// session talks to, until Ctrl-C.
#ifdef TNV_HAVE_SERVE
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <thread>

#include "tools/serve/page_files.hpp"
#include "tools/serve/tuning_server.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_stop_signal(int) { g_stop = true; }

struct ServeCommandOptions {
  int port = 8040;
  std::string bind = "127.0.0.1";
  std::string js_dir = serve::kDefaultJsDir;
  std::string web_dir;  // "" = installed or source tree
};

void check_serve(const ServeCommandOptions& o) {
  if (const std::string missing = serve::missing_page_library(o.js_dir); !missing.empty()) throw BadInput(missing);
}

int run_serve(const ServeCommandOptions& o, Session& session, Report& report) {
  check_serve(o);
  can_host::NodeClient& client = session.client();
  serve::ServeOptions options;
  options.bind = o.bind;
  options.port = o.port;
  options.js_dir = o.js_dir;
  options.web_dir = o.web_dir.empty() ? serve::page_asset_dir() : o.web_dir;
  options.info = {{"node", session.options().node},
                  {"host_id", session.options().host_id},
                  {"bus", client.bus().describe()},
                  {"emulated", session.is_emulated()}};
  serve::TuningServer server(client, session.emulated(), options);
  int port = 0;
  try {
    port = server.start();
  } catch (const std::runtime_error& e) {
    throw BadInput(e.what());
  }
  const std::string host = o.bind == "0.0.0.0" ? "127.0.0.1" : o.bind;
  std::printf("tnvctl serve: http://%s:%d/ (node %d on %s; Ctrl-C ends)\n", host.c_str(), port, session.options().node,
              client.bus().describe().c_str());
  std::fflush(stdout);
  g_stop = false;
  auto previous_int = std::signal(SIGINT, on_stop_signal);
  auto previous_term = std::signal(SIGTERM, on_stop_signal);
  // A signal handler may only set a flag: this thread turns it into stop().
  std::atomic<bool> served{false};
  std::thread watcher([&] {
    while (!g_stop && !served) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    server.stop();
  });
  server.listen();
  served = true;
  watcher.join();
  server.worker().stop();
  std::signal(SIGINT, previous_int);
  std::signal(SIGTERM, previous_term);
  report.line("tnvctl serve: stopped");
  report.data["port"] = port;
  return kExitOk;
}

}  // namespace

void add_serve_commands(CLI::App& app, ActionSlot& slot) {
  auto o = std::make_shared<ServeCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "serve", "the live tuning page in a web browser: scope, parameters, faults, captures, Bode view; Ctrl-C ends");
  cmd->add_option("--port", o->port, "TCP port; 0 = any free port (the URL is printed)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  cmd->add_option("--bind", o->bind,
                  "address to listen on (the default keeps the page to this machine; 0.0.0.0 opens it to the network)")
      ->capture_default_str();
  cmd->add_option("--js-dir", o->js_dir, "directory holding chart.js/chart.min.js (Debian's libjs-chart.js)")
      ->capture_default_str();
  cmd->add_option("--web-dir", o->web_dir, "the page's own files (default: installed, or the source tree's)");
  cmd->callback([&slot, o] {
    slot = Action{"serve", true, [o](Session& s, Report& r) { return run_serve(*o, s, r); }, [o] { check_serve(*o); }};
  });
}

}  // namespace tnv::tnvctl
#endif
