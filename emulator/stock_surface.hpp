#pragma once
// The stock's top as a height field: a grid of square cells (kCellMm) over
// the stock's rectangle, each holding the height of the material in it
// (the stock top, a pre-drilled hole's floor, or what a tool left). Tiles
// of cells are allocated the first time a tool reaches below the top over
// them, so a stock that covers the whole table costs only where it is cut.
// A cell belongs to a disc (a tool's, a hole's) when its square, clipped to
// the rectangle, overlaps the disc: at the rectangle's edge this is the
// reference plant's rule (the disc overlaps the rectangle) exactly.
#include <array>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "emulator/scenario.hpp"

namespace tnv::emu {

class StockSurface {
 public:
  static constexpr double kCellMm = 0.1;  // the grid's pitch (a helix's 1.27 mm step is 13 cells)
  static constexpr int kTileCells = 64;   // a tile is 64 x 64 cells (6.4 mm square, 32 KiB)

  explicit StockSurface(const StockParams& params);

  // The highest material (its height, mm) in the cells under a disc of
  // radius_mm at (x, y), then every one of them lowered to z_mm: a tool
  // whose point is at (x, y, z) cutting what it meets; -inf when the disc
  // meets no cell of the rectangle. Above the top it only reads.
  double cut(double x_mm, double y_mm, double radius_mm, double z_mm);
  // The highest material under the disc, nothing changed (no allocation).
  double highest_mm(double x_mm, double y_mm, double radius_mm) const noexcept;
  // The material's height in the cell under (x, y); -inf off the rectangle.
  double height_mm(double x_mm, double y_mm) const noexcept;
  // The highest the material is anywhere (the stock top): nothing to cut above it.
  double top_mm() const noexcept { return params_.top_mm; }
  std::size_t tiles_allocated() const noexcept { return tiles_.size(); }

 private:
  using Tile = std::array<double, static_cast<std::size_t>(kTileCells) * kTileCells>;
  struct Axis {  // one grid axis: cell i covers [origin + i c, origin + (i + 1) c] clipped to [min, max]
    double origin_mm, min_mm, max_mm;
    std::int64_t first, last;  // the cells with material ([first, last]; the int64 range when unbounded)
    double lo_mm(std::int64_t i) const noexcept;
    double hi_mm(std::int64_t i) const noexcept;
    double centre_mm(std::int64_t i) const noexcept { return 0.5 * (lo_mm(i) + hi_mm(i)); }
    std::int64_t cell_of(double v_mm) const noexcept;
  };
  struct Range {
    std::int64_t i0, i1, j0, j1;
    bool empty() const noexcept { return i0 > i1 || j0 > j1; }
  };
  struct Span {  // the cells [i0, i1] of one row of a Range under a disc (empty: i0 > i1)
    std::int64_t i0, i1;
  };
  // Calls visit(j, span) for each row j of r that the disc overlaps.
  template <typename Visit>
  void for_each_row(const Range& r, double x_mm, double y_mm, double radius_mm, Visit&& visit) const;
  Span row_span(const Range& r, double x_mm, double dy2_mm2, double r2_mm2) const noexcept;
  Range cells_near(double x_mm, double y_mm, double radius_mm) const noexcept;
  static std::uint64_t tile_key(std::int64_t ti, std::int64_t tj) noexcept;
  const Tile* find_tile(std::int64_t ti, std::int64_t tj) const noexcept;
  Tile& tile(std::int64_t ti, std::int64_t tj);
  double initial_height_mm(std::int64_t i, std::int64_t j) const noexcept;
  double cell_height_mm(std::int64_t i, std::int64_t j) const noexcept;

  StockParams params_;
  Axis x_, y_;
  std::unordered_map<std::uint64_t, std::unique_ptr<Tile>> tiles_;
  std::vector<Span> spans_;  // cut()'s rows under the disc (kept: no allocation once grown)
};

}  // namespace tnv::emu
