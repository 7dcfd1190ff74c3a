#pragma once
// Where the page's files are: the web assets (tools/serve/web in the source
// tree, <prefix>/share/tnv/web installed, found like tnvplot's package) and
// the plotting library, Debian's libjs-chart.js.
#include <string>

namespace tnv::serve {

inline constexpr const char* kDefaultJsDir = "/usr/share/javascript";
inline constexpr const char* kChartJsFile = "chart.js/chart.min.js";  // under the JS directory

// The installed copy next to the running program if there is one, else the source tree's.
std::string page_asset_dir();

// "" when `js_dir` holds Chart.js, else what to do about it.
std::string missing_page_library(const std::string& js_dir);

}  // namespace tnv::serve
