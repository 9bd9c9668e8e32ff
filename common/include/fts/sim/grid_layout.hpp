// The cell layout both broad phases share (Grid over boxes, DiscGrid over discs): square
// cells over the bounds of the filed centres, row-major, their number bounded, indices
// clamped; and the half stencil both scan (own cell and the next of its row, the three
// cells above). One rule, so the two cannot drift apart. Grid walks it with the
// edge-aware helpers below; DiscGrid files into the same cells with a ring of empty ones
// around them, so that its scan needs no edge tests (broadphase_discs.cpp).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace fts::sim {

struct GridLayout {
  double origin_x = 0, origin_y = 0, cell = 1, inv_cell = 1;
  std::uint32_t nx = 1, ny = 1;

  // Cells at least `min_cell` wide (a width that is not finite and positive becomes 1)
  // over the centres' bounds [lo_x, hi_x] x [lo_y, hi_y] (non-finite bounds collapse to
  // 0), grown by half until there are at most 4 cells per filed item plus 64: sparse
  // items do not pay for a sea of empty cells.
  static GridLayout fit(double lo_x, double hi_x, double lo_y, double hi_y, double min_cell, std::size_t items) {
    if (!std::isfinite(lo_x) || !std::isfinite(hi_x)) lo_x = hi_x = 0.0;
    if (!std::isfinite(lo_y) || !std::isfinite(hi_y)) lo_y = hi_y = 0.0;
    double cell = (min_cell > 0.0 && std::isfinite(min_cell)) ? min_cell : 1.0;
    const double max_cells = 4.0 * static_cast<double>(items) + 64.0;
    GridLayout g;
    for (;;) {
      const double cx = std::floor((hi_x - lo_x) / cell) + 1.0;
      const double cy = std::floor((hi_y - lo_y) / cell) + 1.0;
      if (cx * cy <= max_cells) {
        g.nx = static_cast<std::uint32_t>(cx);
        g.ny = static_cast<std::uint32_t>(cy);
        break;
      }
      cell *= 1.5;
    }
    g.origin_x = lo_x;
    g.origin_y = lo_y;
    g.cell = cell;
    g.inv_cell = 1.0 / cell;
    return g;
  }

  std::size_t cells() const { return static_cast<std::size_t>(nx) * ny; }
  // The column of x, clamped to the grid (NaN gives 0).
  std::uint32_t column(double x) const { return clamp_index((x - origin_x) * inv_cell, nx - 1); }
  std::uint32_t row(double y) const { return clamp_index((y - origin_y) * inv_cell, ny - 1); }
  std::uint32_t cell_of(double x, double y) const { return row(y) * nx + column(x); }

 private:
  static std::uint32_t clamp_index(double c, std::uint32_t last) {
    if (!(c > 0.0)) return 0;  // also NaN
    return c >= static_cast<double>(last) ? last : static_cast<std::uint32_t>(c);  // floor for c > 0
  }
};

// The half stencil of cell (cx, cy) over slots in cell order, cell k holding
// [begin[k], begin[k + 1]): an item at slot p of the cell tests the slots (p, right_end)
// (the rest of its cell and the next cell of its row) and [up0, up1) (the three cells of
// the row above, one contiguous range; empty on the top row). Every pair of neighbouring
// cells is visited once.
struct HalfStencil {
  std::uint32_t right_end, up0, up1;
};

inline HalfStencil half_stencil(const GridLayout& g, const std::uint32_t* begin, std::uint32_t cx, std::uint32_t cy) {
  const std::uint32_t c = cy * g.nx + cx;
  const bool has_right = cx + 1 < g.nx;
  HalfStencil s{begin[has_right ? c + 2 : c + 1], 0, 0};
  if (cy + 1 < g.ny) {
    s.up0 = begin[c + g.nx - (cx > 0 ? 1 : 0)];
    s.up1 = begin[c + g.nx + (has_right ? 2 : 1)];
  }
  return s;
}

// The scan both broad phases run: fn(p, stencil) for every filed slot p, with the ranges
// its half stencil tests (cells in row order, slots in cell order).
template <class Fn>
inline void for_each_stencil_slot(const GridLayout& g, const std::uint32_t* begin, Fn&& fn) {
  for (std::uint32_t cy = 0; cy < g.ny; ++cy) {
    for (std::uint32_t cx = 0; cx < g.nx; ++cx) {
      const std::uint32_t c = cy * g.nx + cx;
      const std::uint32_t p0 = begin[c], p1 = begin[c + 1];
      if (p0 == p1) continue;
      const HalfStencil stencil = half_stencil(g, begin, cx, cy);
      for (std::uint32_t p = p0; p < p1; ++p) fn(p, stencil);
    }
  }
}

}  // namespace fts::sim
