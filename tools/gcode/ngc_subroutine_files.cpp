#include "tools/gcode/ngc_subroutine_files.hpp"

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tools/gcode/ngc_block.hpp"
#include "tools/gcode/ngc_error.hpp"
#include "tools/gcode/program_file.hpp"

namespace tnv::gcode {

namespace {

bool file_name_safe(const std::string& name) {
  if (name.empty() || name.find_first_not_of("0123456789") == std::string::npos) return false;  // o100: no file
  return name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") == std::string::npos;
}

}  // namespace

SubroutineFiles append_subroutine_files(ProgramLines& lines, const std::vector<std::string>& dirs,
                                        std::size_t& error_line) {
  SubroutineFiles loaded;
  std::set<std::string> defined, looked_up;
  std::size_t scanned = 0;
  // Each pass scans the lines not scanned yet: the program, then each file's definition.
  while (scanned < lines.size()) {
    const std::size_t end = lines.size();
    std::vector<std::pair<std::string, std::size_t>> wanted;  // name, first calling line
    const std::vector<std::pair<std::size_t, NgcOWord>> o_words = o_word_lines(lines, scanned);
    for (const auto& [i, o] : o_words)
      if (o.keyword == OKeyword::sub) defined.insert(o.name);
    for (const auto& [i, o] : o_words)
      if (o.keyword == OKeyword::call && file_name_safe(o.name) && !defined.count(o.name) &&
          looked_up.insert(o.name).second)
        wanted.emplace_back(o.name, i);
    scanned = end;
    for (const auto& [name, caller] : wanted) {
      error_line = caller + 1;
      std::string path;
      for (const std::string& dir : dirs) {
        const std::filesystem::path candidate = std::filesystem::path(dir) / (name + ".ngc");
        std::error_code ec;
        if (std::filesystem::exists(candidate, ec)) {
          path = candidate.string();
          break;
        }
      }
      if (path.empty()) continue;  // the call refuses it if it runs
      if (loaded.files.size() == kMaxSubroutineFiles)
        throw NgcError(1, "o<" + name + "> call: more than " + std::to_string(kMaxSubroutineFiles) +
                              " subroutine files for one program");
      std::string text, why;
      if (!read_program_file(path, text, why)) throw NgcError(1, "o<" + name + "> call: " + why);
      int file_line = 0;  // a line LinuxCNC refuses throws at the calling line, as a read error does
      std::vector<std::string_view> file_lines;
      ProgramLines::split_checked(text, file_line, file_lines);
      std::optional<std::size_t> sub, endsub;
      for (std::size_t k = 0; k < file_lines.size() && !endsub; ++k) {
        const auto o = raw_o_word(file_lines[k]);
        if (!o || o->name != name) continue;
        if (o->keyword == OKeyword::sub && !sub) sub = k;
        else if (o->keyword == OKeyword::endsub && sub) endsub = k;
      }
      if (!sub || !endsub)
        throw NgcError(1, "o<" + name + "> call: " + path + " has no o<" + name + "> sub ... o<" + name +
                              "> endsub");
      loaded.files.push_back(path);
      // Only the definition's text is kept (the rest of the file never runs).
      const auto def_begin = static_cast<std::size_t>(file_lines[*sub].data() - text.data());
      const auto def_end = static_cast<std::size_t>(file_lines[*endsub].data() + file_lines[*endsub].size() - text.data());
      std::vector<std::string_view> definition;
      int definition_line = 0;
      ProgramLines::split_checked(lines.keep(text.substr(def_begin, def_end - def_begin)), definition_line, definition);
      for (std::size_t k = 0; k < definition.size(); ++k) {
        lines.append(definition[k]);
        loaded.origins.push_back({loaded.files.size() - 1, static_cast<int>(*sub + k + 1)});
      }
      defined.insert(name);
    }
  }
  return loaded;
}

}  // namespace tnv::gcode
