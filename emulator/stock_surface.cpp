#include "emulator/stock_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tnv::emu {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Far enough for any machine coordinate (1e12 cells = 1e8 m), small enough
// that cell indices and their tile numbers stay exact in int64 and double.
constexpr std::int64_t kUnboundedCells = 1'000'000'000'000;

// The grid's origin on one axis: the rectangle's low edge, else its high
// edge, else 0, so the cells tile a finite rectangle from its corner.
double grid_origin_mm(double min_mm, double max_mm) noexcept {
  if (std::isfinite(min_mm)) return min_mm;
  if (std::isfinite(max_mm)) return max_mm;
  return 0.0;
}

std::int64_t floor_div(std::int64_t a, std::int64_t b) noexcept { return a >= 0 ? a / b : -((-a + b - 1) / b); }

}  // namespace

double StockSurface::Axis::lo_mm(std::int64_t i) const noexcept {
  return std::max(origin_mm + static_cast<double>(i) * kCellMm, min_mm);
}
double StockSurface::Axis::hi_mm(std::int64_t i) const noexcept {
  return std::min(origin_mm + static_cast<double>(i + 1) * kCellMm, max_mm);
}
std::int64_t StockSurface::Axis::cell_of(double v_mm) const noexcept {
  const double i = std::floor((v_mm - origin_mm) / kCellMm);
  return static_cast<std::int64_t>(std::clamp(i, static_cast<double>(-kUnboundedCells), static_cast<double>(kUnboundedCells)));
}

StockSurface::StockSurface(const StockParams& params) : params_(params) {
  const auto axis = [](double min_mm, double max_mm) {
    Axis a{grid_origin_mm(min_mm, max_mm), min_mm, max_mm, -kUnboundedCells, kUnboundedCells};
    if (std::isfinite(min_mm)) a.first = a.cell_of(min_mm);
    if (std::isfinite(max_mm)) {
      // The last cell starts below max (a cell of zero width is no cell).
      a.last = static_cast<std::int64_t>(std::ceil((max_mm - a.origin_mm) / kCellMm)) - 1;
    }
    return a;
  };
  x_ = axis(params.x_min_mm, params.x_max_mm);
  y_ = axis(params.y_min_mm, params.y_max_mm);
}

StockSurface::Range StockSurface::cells_near(double x_mm, double y_mm, double radius_mm) const noexcept {
  return Range{std::max(x_.cell_of(x_mm - radius_mm), x_.first), std::min(x_.cell_of(x_mm + radius_mm), x_.last),
               std::max(y_.cell_of(y_mm - radius_mm), y_.first), std::min(y_.cell_of(y_mm + radius_mm), y_.last)};
}

// A cell overlaps the disc when its (clipped) square does. Along a row the
// distance from x to a cell's square falls, then rises (its low edge minus
// x grows, x minus its high edge shrinks), so the cells under the disc are
// one run. Its ends are first guessed from the chord's half-width, then
// moved cell by cell with the exact test until it holds inside and fails
// outside; a row the disc misses ends with first > last.
StockSurface::Span StockSurface::row_span(const Range& r, double x_mm, double dy2_mm2, double r2_mm2) const noexcept {
  const auto in_disc = [&](std::int64_t i) {
    const double dx = std::max({x_.lo_mm(i) - x_mm, 0.0, x_mm - x_.hi_mm(i)});
    return dx * dx + dy2_mm2 < r2_mm2;
  };
  const double half_mm = std::sqrt(std::max(r2_mm2 - dy2_mm2, 0.0));
  // The cell nearest x (within one of the cell x falls in, clamped to the row).
  const std::int64_t near = std::clamp(x_.cell_of(x_mm), r.i0, r.i1);
  std::int64_t first = std::clamp(x_.cell_of(x_mm - half_mm), r.i0, near);
  std::int64_t last = std::clamp(x_.cell_of(x_mm + half_mm), near, r.i1);
  while (first > r.i0 && in_disc(first - 1)) --first;
  while (first <= last && !in_disc(first)) ++first;
  while (last < r.i1 && in_disc(last + 1)) ++last;
  while (last >= first && !in_disc(last)) --last;
  return Span{first, last};
}

template <typename Visit>
void StockSurface::for_each_row(const Range& r, double x_mm, double y_mm, double radius_mm, Visit&& visit) const {
  const double r2 = radius_mm * radius_mm;
  for (std::int64_t j = r.j0; j <= r.j1; ++j) {
    const double dy = std::max({y_.lo_mm(j) - y_mm, 0.0, y_mm - y_.hi_mm(j)});
    const double dy2 = dy * dy;
    if (!(dy2 < r2)) continue;
    const Span span = row_span(r, x_mm, dy2, r2);
    if (span.i0 <= span.i1) visit(j, span);
  }
}

std::uint64_t StockSurface::tile_key(std::int64_t ti, std::int64_t tj) noexcept {
  return (static_cast<std::uint64_t>(ti) << 32U) ^ static_cast<std::uint64_t>(static_cast<std::uint32_t>(tj));
}

const StockSurface::Tile* StockSurface::find_tile(std::int64_t ti, std::int64_t tj) const noexcept {
  const auto found = tiles_.find(tile_key(ti, tj));
  return found == tiles_.end() ? nullptr : found->second.get();
}

StockSurface::Tile& StockSurface::tile(std::int64_t ti, std::int64_t tj) {
  std::unique_ptr<Tile>& slot = tiles_[tile_key(ti, tj)];
  if (!slot) {
    slot = std::make_unique<Tile>();
    for (int b = 0; b < kTileCells; ++b) {
      for (int a = 0; a < kTileCells; ++a) {
        (*slot)[static_cast<std::size_t>(b) * kTileCells + static_cast<std::size_t>(a)] =
            initial_height_mm(ti * kTileCells + a, tj * kTileCells + b);
      }
    }
  }
  return *slot;
}

// The top, or the floor of a hole whose disc overlaps the cell (a drill
// takes what a tool of its diameter would).
double StockSurface::initial_height_mm(std::int64_t i, std::int64_t j) const noexcept {
  double h = params_.top_mm;
  for (const StockHole& hole : params_.holes) {
    const double dx = std::max({x_.lo_mm(i) - hole.x_mm, 0.0, hole.x_mm - x_.hi_mm(i)});
    const double dy = std::max({y_.lo_mm(j) - hole.y_mm, 0.0, hole.y_mm - y_.hi_mm(j)});
    const double radius_mm = 0.5 * hole.diameter_mm;
    if (dx * dx + dy * dy < radius_mm * radius_mm) h = std::min(h, params_.top_mm - hole.depth_mm);
  }
  return h;
}

double StockSurface::cell_height_mm(std::int64_t i, std::int64_t j) const noexcept {
  if (i < x_.first || i > x_.last || j < y_.first || j > y_.last) return -kInf;
  const std::int64_t ti = floor_div(i, kTileCells);
  const std::int64_t tj = floor_div(j, kTileCells);
  const Tile* t = find_tile(ti, tj);
  if (t == nullptr) return initial_height_mm(i, j);
  return (*t)[static_cast<std::size_t>(j - tj * kTileCells) * kTileCells + static_cast<std::size_t>(i - ti * kTileCells)];
}

double StockSurface::cut(double x_mm, double y_mm, double radius_mm, double z_mm) {
  const Range r = cells_near(x_mm, y_mm, radius_mm);
  double highest = -kInf;
  if (r.empty() || !(z_mm < params_.top_mm)) return r.empty() ? highest : highest_mm(x_mm, y_mm, radius_mm);
  spans_.assign(static_cast<std::size_t>(r.j1 - r.j0 + 1), Span{1, 0});
  for_each_row(r, x_mm, y_mm, radius_mm,
               [&](std::int64_t j, const Span& span) { spans_[static_cast<std::size_t>(j - r.j0)] = span; });
  // Tile by tile: one map look-up per tile, each row's run in it by index.
  for (std::int64_t tj = floor_div(r.j0, kTileCells); tj <= floor_div(r.j1, kTileCells); ++tj) {
    const std::int64_t j0 = std::max(r.j0, tj * kTileCells), j1 = std::min(r.j1, tj * kTileCells + kTileCells - 1);
    for (std::int64_t ti = floor_div(r.i0, kTileCells); ti <= floor_div(r.i1, kTileCells); ++ti) {
      const std::int64_t tile_i0 = ti * kTileCells, tile_i1 = tile_i0 + kTileCells - 1;
      Tile* t = nullptr;
      for (std::int64_t j = j0; j <= j1; ++j) {
        const Span& span = spans_[static_cast<std::size_t>(j - r.j0)];
        const std::int64_t i0 = std::max(span.i0, tile_i0), i1 = std::min(span.i1, tile_i1);
        if (i0 > i1) continue;
        if (t == nullptr) t = &tile(ti, tj);  // the tool is below the top over it: filled once, read since
        double* row = t->data() + static_cast<std::size_t>(j - tj * kTileCells) * kTileCells;
        for (std::int64_t i = i0 - tile_i0; i <= i1 - tile_i0; ++i) {
          double& h = row[i];
          highest = std::max(highest, h);
          h = std::min(h, z_mm);
        }
      }
    }
  }
  return highest;
}

double StockSurface::highest_mm(double x_mm, double y_mm, double radius_mm) const noexcept {
  const Range r = cells_near(x_mm, y_mm, radius_mm);
  double highest = -kInf;
  if (r.empty()) return highest;
  for_each_row(r, x_mm, y_mm, radius_mm, [&](std::int64_t j, const Span& span) {
    for (std::int64_t i = span.i0; i <= span.i1; ++i) highest = std::max(highest, cell_height_mm(i, j));
  });
  return highest;
}

double StockSurface::height_mm(double x_mm, double y_mm) const noexcept {
  return cell_height_mm(x_.cell_of(x_mm), y_.cell_of(y_mm));
}

}  // namespace tnv::emu
