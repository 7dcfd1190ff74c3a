#include "tools/can_emu/emulated_storage_path.hpp"

#include <cstdlib>
#include <filesystem>

namespace tnv::can_host {

namespace fs = std::filesystem;

std::string default_emulated_storage_path() {
  fs::path dir;
  if (const char* state = std::getenv("XDG_STATE_HOME"); state != nullptr && state[0] == '/') {
    dir = fs::path(state) / "tnvctl";
  } else if (const char* home = std::getenv("HOME"); home != nullptr && home[0] != '\0') {
    dir = fs::path(home) / ".local" / "state" / "tnvctl";
  }
  return (dir / "emu-node.params").string();
}

}  // namespace tnv::can_host
