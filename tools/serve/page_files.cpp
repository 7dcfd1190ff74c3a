#include "tools/serve/page_files.hpp"

#include <filesystem>

namespace tnv::serve {

namespace fs = std::filesystem;

std::string page_asset_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / TNV_SERVE_WEB_INSTALL_REL_DIR;
    if (fs::exists(installed / "index.html", ec)) return installed.string();
  }
  return TNV_SERVE_WEB_SOURCE_DIR;
}

std::string missing_page_library(const std::string& js_dir) {
  std::error_code ec;
  const fs::path chart = fs::path(js_dir) / kChartJsFile;
  if (fs::is_regular_file(chart, ec)) return "";
  std::string message = "the page's plotting library is missing: no ";
  message.append(chart.string()).append(" (install Debian's libjs-chart.js, or give --js-dir DIR holding ");
  return message.append(kChartJsFile).append(")");
}

}  // namespace tnv::serve
