#pragma once
// A minimal SVG document builder: just what the plots need.
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tnv::hil {

class SvgWriter {
 public:
  SvgWriter(double width_px, double height_px);

  void line(double x1, double y1, double x2, double y2, std::string_view stroke, double width = 1.0,
            std::string_view dash = {});
  void rect(double x, double y, double w, double h, std::string_view stroke, std::string_view fill = "none");
  void circle(double cx, double cy, double r, std::string_view stroke, double width = 1.0,
              std::string_view dash = {});
  void polyline(const std::vector<std::pair<double, double>>& points, std::string_view stroke, double width = 1.0);
  // anchor: "start", "middle" or "end"
  void text(double x, double y, std::string_view content, double size_px = 12.0, std::string_view anchor = "start",
            std::string_view fill = "#222", double rotate_deg = 0.0);

  std::string str() const;
  // Writes the document; returns false (with reason) when the file cannot be written.
  bool save(const std::string& path, std::string& error) const;

 private:
  double width_px_;
  double height_px_;
  std::ostringstream body_;
};

}  // namespace tnv::hil
