#include "tools/cli/run_plotter.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "tools/cli/output_path.hpp"

extern char** environ;

namespace tnv::cli {

namespace fs = std::filesystem;

namespace {

constexpr const char* kPython = "/usr/bin/python3";
constexpr const char* kPlotPackages = "python3-matplotlib python3-numpy";

// The environment with PYTHONPATH naming only the package's directory.
std::vector<std::string> plotter_environment(const std::string& package_dir) {
  std::vector<std::string> env;
  for (char** e = environ; *e != nullptr; ++e)
    if (std::strncmp(*e, "PYTHONPATH=", 11) != 0 && std::strncmp(*e, "PYTHONHOME=", 11) != 0) env.emplace_back(*e);
  env.push_back("PYTHONPATH=" + package_dir);
  return env;
}

std::vector<char*> c_strings(std::vector<std::string>& strings) {
  std::vector<char*> out;
  for (std::string& s : strings) out.push_back(s.data());
  out.push_back(nullptr);
  return out;
}

}  // namespace

std::string plot_package_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / TNV_PLOT_INSTALL_REL_DIR;
    if (fs::exists(installed / "tnvplot" / "__init__.py", ec)) return installed.string();
  }
  return TNV_PLOT_SOURCE_DIR;
}

std::string plot_data_path(const std::string& figure, const char* suffix) {
  fs::path p(figure);
  p.replace_extension(suffix);
  return p.string();
}

std::string run_plotter(const std::string& kind, const std::vector<std::string>& inputs, const std::string& output,
                        const std::vector<std::string>& extra) {
  std::vector<std::string> args = {kPython, "-s", "-B", "-m", "tnvplot", kind};
  args.insert(args.end(), inputs.begin(), inputs.end());
  args.push_back(output);
  args.insert(args.end(), extra.begin(), extra.end());
  std::vector<std::string> env = plotter_environment(plot_package_dir());
  std::vector<char*> argv = c_strings(args);
  std::vector<char*> envp = c_strings(env);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);  // stdout may carry --json
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, kPython, &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0)
    return output + ": cannot run " + kPython + " (" + std::strerror(spawned) + "): install Debian's python3 and " +
           kPlotPackages;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return output + ": lost the plotter (" + std::strerror(errno) + ")";
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return {};
  if (WIFEXITED(status) && WEXITSTATUS(status) == 3)
    return output + ": not drawn: matplotlib or numpy is missing (install Debian's " + kPlotPackages + ")";
  if (WIFSIGNALED(status)) return output + ": not drawn: the plotter died of signal " + std::to_string(WTERMSIG(status));
  return output + ": not drawn: the plotter (" + kPython + " -m tnvplot " + kind + ") exited with status " +
         std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1);
}

bool plot_json(const std::string& figure, const nlohmann::json& data, const char* tool) {
  const std::string data_path = plot_data_path(figure);
  if (!write_file_replacing(data_path, data.dump())) {
    std::fprintf(stderr, "%s: %s: cannot write\n", tool, data_path.c_str());
    return false;
  }
  return plot_files(figure, data.value("kind", "panels"), {data_path}, {}, tool);
}

bool plot_files(const std::string& figure, const std::string& kind, const std::vector<std::string>& inputs,
                const std::vector<std::string>& extra, const char* tool) {
  const std::string error = run_plotter(kind, inputs, figure, extra);
  if (!error.empty()) {
    std::fprintf(stderr, "%s: %s\n", tool, error.c_str());
    return false;
  }
  std::fprintf(stderr, "[plot] wrote %s\n", figure.c_str());
  return true;
}

}  // namespace tnv::cli
