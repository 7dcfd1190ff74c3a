#pragma once
// Each tnv-hil command family registers its subcommands here. A
// subcommand's callback sets `run`; main() calls it after parsing.
#include <CLI/CLI.hpp>

#include "tools/tnv-hil/cli_support.hpp"

namespace tnv::cli {

void add_circle_commands(CLI::App& app, Runner& run);  // circle, table3, plant-check (S1)

}  // namespace tnv::cli
