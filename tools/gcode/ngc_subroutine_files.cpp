#include "tools/gcode/ngc_subroutine_files.hpp"

#include <filesystem>
#include <optional>
#include <set>

#include "tools/gcode/ngc_block.hpp"
#include "tools/gcode/ngc_error.hpp"
#include "tools/gcode/program_file.hpp"

namespace tnv::gcode {

namespace {

std::optional<NgcOWord> o_word(const NgcLine& line) {
  try {
    NgcOWord o = scan_o_word(line);
    if (o.keyword != OKeyword::none) return o;
  } catch (const NgcError&) {
    // reported when the line runs
  }
  return std::nullopt;
}

bool file_name_safe(const std::string& name) {
  if (name.empty() || name.find_first_not_of("0123456789") == std::string::npos) return false;  // o100: no file
  return name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") == std::string::npos;
}

}  // namespace

SubroutineFiles append_subroutine_files(std::vector<NgcLine>& lines, const std::vector<std::string>& dirs,
                                        std::size_t& error_line) {
  SubroutineFiles loaded;
  std::set<std::string> defined, looked_up;
  std::size_t scanned = 0;
  // Each pass scans the lines not scanned yet: the program, then each file's definition.
  while (scanned < lines.size()) {
    const std::size_t end = lines.size();
    std::vector<std::pair<std::string, std::size_t>> wanted;  // name, first calling line
    for (std::size_t i = scanned; i < end; ++i)
      if (const auto o = o_word(lines[i]); o && o->keyword == OKeyword::sub) defined.insert(o->name);
    for (std::size_t i = scanned; i < end; ++i)
      if (const auto o = o_word(lines[i]); o && o->keyword == OKeyword::call && file_name_safe(o->name) &&
                                           !defined.count(o->name) && looked_up.insert(o->name).second)
        wanted.emplace_back(o->name, i);
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
      const std::vector<NgcLine> file_lines = normalize_lines(text, file_line);
      std::optional<std::size_t> sub, endsub;
      for (std::size_t k = 0; k < file_lines.size() && !endsub; ++k) {
        const auto o = o_word(file_lines[k]);
        if (!o || o->name != name) continue;
        if (o->keyword == OKeyword::sub && !sub) sub = k;
        else if (o->keyword == OKeyword::endsub && sub) endsub = k;
      }
      if (!sub || !endsub)
        throw NgcError(1, "o<" + name + "> call: " + path + " has no o<" + name + "> sub ... o<" + name +
                              "> endsub");
      loaded.files.push_back(path);
      for (std::size_t k = *sub; k <= *endsub; ++k) {
        lines.push_back(file_lines[k]);
        loaded.origins.push_back({loaded.files.size() - 1, static_cast<int>(k + 1)});
      }
      defined.insert(name);
    }
  }
  return loaded;
}

}  // namespace tnv::gcode
