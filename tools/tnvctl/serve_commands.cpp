// tnvctl serve: the live tuning page (tools/serve) for the node this
// session talks to, until Ctrl-C.
#ifdef TNV_HAVE_SERVE
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <thread>

#include "tools/serve/access_gate.hpp"
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
  std::string token_file;  // "" = a new secret at each start
  std::string tls_cert;
  std::string tls_key;
  std::string audit;  // "" = stderr
  bool read_only = false;
  int deadman_ms = 300;
  int max_program_kib = 4096;
};

void check_serve(const ServeCommandOptions& o) {
  if (const std::string missing = serve::missing_page_library(o.js_dir); !missing.empty()) throw BadInput(missing);
  if (const std::string why = serve::bind_refusal(o.bind, o.tls_cert, o.tls_key); !why.empty()) throw BadInput(why);
  if (!o.token_file.empty()) {
    try {
      serve::read_secret_file(o.token_file);
    } catch (const std::runtime_error& e) {
      throw BadInput(e.what());
    }
  }
}

int run_serve(const ServeCommandOptions& o, Session& session, Report& report) {
  check_serve(o);
  can_host::NodeClient& client = session.client();
  serve::ServeOptions options;
  options.bind = o.bind;
  options.port = o.port;
  options.js_dir = o.js_dir;
  options.web_dir = o.web_dir.empty() ? serve::page_asset_dir() : o.web_dir;
  options.tls_cert = o.tls_cert;
  options.tls_key = o.tls_key;
  options.audit_path = o.audit;
  options.read_only = o.read_only;
  options.control_deadman = std::chrono::milliseconds(o.deadman_ms);
  options.max_program_bytes = static_cast<std::size_t>(o.max_program_kib) * 1024;
  options.info = {{"node", session.options().node},
                  {"host_id", session.options().host_id},
                  {"bus", client.bus().describe()},
                  {"emulated", session.is_emulated()}};
  std::unique_ptr<serve::TuningServer> made;
  int port = 0;
  try {
    if (!o.token_file.empty()) options.secret = serve::read_secret_file(o.token_file);
    made = std::make_unique<serve::TuningServer>(client, session.emulated(), options);
    port = made->start();
  } catch (const std::runtime_error& e) {
    throw BadInput(e.what());
  }
  serve::TuningServer& server = *made;
  const std::string host = o.bind == "0.0.0.0" ? "127.0.0.1" : o.bind == "::" ? "::1" : o.bind;
  // The secret is in the URL (as Jupyter prints it): whoever can read this terminal may use the page.
  std::printf("tnvctl serve: %s (node %d on %s%s; Ctrl-C ends)\n", server.page_url(host, port).c_str(),
              session.options().node, client.bus().describe().c_str(), o.read_only ? "; read-only" : "");
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
                  "address to listen on (the default keeps the page to this machine; any other address needs --tls-cert/--tls-key)")
      ->capture_default_str();
  cmd->add_option("--js-dir", o->js_dir, "directory holding chart.js/chart.min.js (Debian's libjs-chart.js)")
      ->capture_default_str();
  cmd->add_option("--web-dir", o->web_dir, "the page's own files (default: installed, or the source tree's)");
  cmd->add_option("--token-file", o->token_file,
                  "a fixed secret (>= 32 characters, e.g. `openssl rand -hex 32`) in a file only its owner may read "
                  "(chmod 600); default: a new secret at each start, printed in the URL");
  cmd->add_option("--tls-cert", o->tls_cert, "PEM certificate: serve HTTPS (needed for a non-loopback --bind)");
  cmd->add_option("--tls-key", o->tls_key, "PEM private key of --tls-cert");
  cmd->add_option("--audit", o->audit,
                  "append the audit trail (every command and change, JSON lines) to this file; default stderr");
  cmd->add_option("--deadman-ms", o->deadman_ms,
                  "the tab with control that is not heard from for this long loses it, and its motion is stopped")
      ->check(CLI::Range(100, 10000))
      ->capture_default_str();
  cmd->add_option("--max-program-kib", o->max_program_kib,
                  "the largest program the page's Program panel may send (its request body; other requests: 64 KiB)")
      ->check(CLI::Range(64, 1024 * 1024))
      ->capture_default_str();
  cmd->add_flag("--read-only", o->read_only, "a second screen: the page may watch, never command or change");
  cmd->callback([&slot, o] {
    slot = Action{"serve", true, [o](Session& s, Report& r) { return run_serve(*o, s, r); }, [o] { check_serve(*o); }};
  });
}

}  // namespace tnv::tnvctl
#endif
