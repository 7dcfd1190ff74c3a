#pragma once
// Where `tnvctl --emu` keeps the emulated node's parameter image (the files
// themselves are drivers::FileParamStorage's: current + previous generation).
#include <string>

namespace tnv::can_host {

// $XDG_STATE_HOME/tnvctl/emu-node.params, or ~/.local/state/tnvctl/emu-node.params
// (XDG base directory spec); "emu-node.params" in the working directory when
// neither variable is set.
std::string default_emulated_storage_path();

}  // namespace tnv::can_host
