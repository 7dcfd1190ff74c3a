#pragma once
// What every command-line tool of the project does the same way: a
// --version flag, and a parse error said on one line that names the tool
// ("tnvctl: unknown command 'bogus' ..."), not CLI11's bare message.
#include <CLI/CLI.hpp>
#include <string>

namespace tnv::cli {

// "<tool> <project version>", e.g. "tnvctl 0.1.0".
std::string version_text(const char* tool);

// --version prints version_text(tool) and exits 0.
void add_version_flag(CLI::App& app, const char* tool);

// What went wrong, in one line: a word where a command was expected is
// named, with the commands there are; otherwise CLI11's message.
std::string describe_parse_error(CLI::App& app, const CLI::ParseError& e);

// For the exception app.parse() threw: help and --version go to stdout and
// give 0; every other error goes to stderr as "<tool>: <what went wrong>"
// (describe_parse_error) plus where to look, and gives `bad_input_code`.
int report_parse_error(CLI::App& app, const CLI::ParseError& e, const char* tool, int bad_input_code);

}  // namespace tnv::cli
