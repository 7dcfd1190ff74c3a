#include "tools/hil/svg_writer.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iomanip>

namespace tnv::hil {

namespace {
std::string escape(std::string_view s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}
}  // namespace

SvgWriter::SvgWriter(double width_px, double height_px) : width_px_(width_px), height_px_(height_px) {
  body_ << std::fixed << std::setprecision(1);
}

void SvgWriter::line(double x1, double y1, double x2, double y2, std::string_view stroke, double width,
                     std::string_view dash) {
  body_ << "<line x1=\"" << x1 << "\" y1=\"" << y1 << "\" x2=\"" << x2 << "\" y2=\"" << y2 << "\" stroke=\""
        << stroke << "\" stroke-width=\"" << width << "\"";
  if (!dash.empty()) body_ << " stroke-dasharray=\"" << dash << "\"";
  body_ << "/>\n";
}

void SvgWriter::rect(double x, double y, double w, double h, std::string_view stroke, std::string_view fill) {
  body_ << "<rect x=\"" << x << "\" y=\"" << y << "\" width=\"" << w << "\" height=\"" << h << "\" stroke=\""
        << stroke << "\" fill=\"" << fill << "\"/>\n";
}

void SvgWriter::circle(double cx, double cy, double r, std::string_view stroke, double width, std::string_view dash) {
  body_ << "<circle cx=\"" << cx << "\" cy=\"" << cy << "\" r=\"" << r << "\" fill=\"none\" stroke=\"" << stroke
        << "\" stroke-width=\"" << width << "\"";
  if (!dash.empty()) body_ << " stroke-dasharray=\"" << dash << "\"";
  body_ << "/>\n";
}

void SvgWriter::polyline(const std::vector<std::pair<double, double>>& points, std::string_view stroke,
                         double width) {
  if (points.empty()) return;
  body_ << "<polyline fill=\"none\" stroke=\"" << stroke << "\" stroke-width=\"" << width
        << "\" stroke-linejoin=\"round\" points=\"";
  for (const auto& [x, y] : points) body_ << x << ',' << y << ' ';
  body_ << "\"/>\n";
}

void SvgWriter::text(double x, double y, std::string_view content, double size_px, std::string_view anchor,
                     std::string_view fill, double rotate_deg) {
  body_ << "<text x=\"" << x << "\" y=\"" << y << "\" font-size=\"" << size_px << "\" text-anchor=\"" << anchor
        << "\" fill=\"" << fill << "\"";
  if (rotate_deg != 0.0) body_ << " transform=\"rotate(" << rotate_deg << ' ' << x << ' ' << y << ")\"";
  body_ << ">" << escape(content) << "</text>\n";
}

std::string SvgWriter::str() const {
  std::ostringstream doc;
  doc << std::fixed << std::setprecision(0);
  doc << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width_px_ << "\" height=\"" << height_px_
      << "\" viewBox=\"0 0 " << width_px_ << ' ' << height_px_
      << "\" font-family=\"DejaVu Sans, Arial, sans-serif\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << body_.str() << "</svg>\n";
  return doc.str();
}

bool SvgWriter::save(const std::string& path, std::string& error) const {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) {
    error = path + ": cannot open for writing: " + std::strerror(errno);
    return false;
  }
  out << str();
  out.close();
  if (!out) {
    error = path + ": write failed";
    return false;
  }
  return true;
}

}  // namespace tnv::hil
