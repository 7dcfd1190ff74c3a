#include "tools/tune/freq_response.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tnv::tune {

namespace {

double coherence(std::complex<double> s_xd, double s_xx, double s_dd) noexcept {
  const double denominator = s_xx * s_dd;
  if (!(denominator > 0.0)) return 0.0;
  return std::clamp(std::norm(s_xd) / denominator, 0.0, 1.0);
}

}  // namespace

const char* to_string(LoopKind kind) noexcept {
  switch (kind) {
    case LoopKind::plant: return "plant";
    case LoopKind::open: return "open";
    case LoopKind::closed: return "closed";
  }
  return "?";
}

bool parse_loop_kind(const std::string& text, LoopKind& out) noexcept {
  for (const LoopKind k : {LoopKind::plant, LoopKind::open, LoopKind::closed})
    if (text == to_string(k)) {
      out = k;
      return true;
    }
  return false;
}

std::vector<ResponsePoint> loop_response(const std::vector<SpectraPoint>& spectra, LoopKind kind) {
  std::vector<ResponsePoint> out;
  out.reserve(spectra.size());
  for (const SpectraPoint& p : spectra) {
    ResponsePoint r;
    r.freq_hz = p.freq_hz;
    const double g_yd = coherence(p.s_yd, p.s_yy, p.s_dd);
    const double g_ud = coherence(p.s_ud, p.s_uu, p.s_dd);
    const double g_cd = coherence(p.s_cd, p.s_cc, p.s_dd);
    switch (kind) {
      case LoopKind::plant:
        r.response = p.s_yd / p.s_ud;
        r.coherence = std::min(g_yd, g_ud);
        break;
      case LoopKind::open:
        r.response = -p.s_cd / p.s_ud;
        r.coherence = std::min(g_cd, g_ud);
        break;
      case LoopKind::closed:
        r.response = -p.s_cd / p.s_dd;
        r.coherence = g_cd;
        break;
    }
    out.push_back(r);
  }
  return out;
}

double gain_db(std::complex<double> h) noexcept { return 20.0 * std::log10(std::abs(h)); }

double phase_deg(std::complex<double> h) noexcept { return std::arg(h) * 180.0 / std::numbers::pi; }

}  // namespace tnv::tune
