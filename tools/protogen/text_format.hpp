#pragma once
// Small text helpers shared by the DBC and Markdown writers.
#include <cstdio>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tnv::protogen {

// out += each part (avoids "literal" + std::string chains).
template <typename... Parts>
void append(std::string& out, const Parts&... parts) {
  (out.append(std::string_view(parts)), ...);
}

// %.7g: the precision of the float32 values on the wire.
inline std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.7g", v);
  return buf;
}

inline std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  return out;
}

// "0=a 1=b -1=none" -> {{0,"a"},{1,"b"},{-1,"none"}}
inline std::vector<std::pair<long, std::string>> value_table(std::string_view values) {
  std::vector<std::pair<long, std::string>> out;
  std::size_t i = 0;
  while (i < values.size()) {
    while (i < values.size() && values[i] == ' ') ++i;
    const std::size_t eq = values.find('=', i);
    if (eq == std::string_view::npos) break;
    std::size_t end = values.find(' ', eq);
    if (end == std::string_view::npos) end = values.size();
    out.emplace_back(std::stol(std::string(values.substr(i, eq - i))), std::string(values.substr(eq + 1, end - eq - 1)));
    i = end;
  }
  return out;
}

}  // namespace tnv::protogen
