// Broad phase for many discs of similar size (the gas, the game): every call copies the
// discs into cell order (a counting sort into structure-of-arrays buffers), then each
// disc tests two contiguous ranges: the rest of its own cell plus the next cell of its
// row, and the three cells of the row above. That half stencil visits every pair of
// neighbouring cells once. Each range is first tested as a window of fixed width, two
// slots at a time and without branches (the ranges are short and their lengths random,
// so a loop over them mispredicts its exit at nearly every disc); only a window with a
// touching pair in it, or a range longer than the window, is walked pair by pair. Cells are at least one largest diameter wide, so touching
// discs always sit in the same or neighbouring cells. Discs far larger than the mean
// (a giant, a boss) are kept aside and tested against every disc, so one of them does
// not blow up the cell size.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "fts/sim/ball.hpp"
#include "fts/sim/grid_layout.hpp"

namespace fts::sim {

// What filing needs before it can lay out the cells: the radii (sum and largest) and the
// centres' bounds. A caller that passes over the balls anyway (a model's move) adds each
// ball as it goes and hands the result to touching_pairs, which then skips that pass.
struct DiscBounds {
  double sum_r = 0.0, r_max = 0.0;
  double lo_x = std::numeric_limits<double>::infinity(), hi_x = -std::numeric_limits<double>::infinity();
  double lo_y = std::numeric_limits<double>::infinity(), hi_y = -std::numeric_limits<double>::infinity();
  void add(const Ball& b) {
    sum_r += b.radius;
    r_max = std::max(r_max, b.radius);
    lo_x = std::min(lo_x, b.pos.x); hi_x = std::max(hi_x, b.pos.x);
    lo_y = std::min(lo_y, b.pos.y); hi_y = std::max(hi_y, b.pos.y);
  }
};

class DiscGrid {
 public:
  // Appends to `out` every index pair (i < j) with |p_j - p_i|^2 <= (r_i + r_j)^2, the
  // exact test of the pairs mode, in no particular order. `bounds`, if given, must be
  // the DiscBounds of exactly these balls.
  void touching_pairs(const std::vector<Ball>& balls, std::vector<std::pair<std::uint32_t, std::uint32_t>>& out,
                      const DiscBounds* bounds = nullptr);

 private:
  void file(const std::vector<Ball>& balls, const DiscBounds& bounds);

  // The cells are grid_'s with a ring of empty cells around them (grid_.nx + 2 columns,
  // grid_.ny + 2 rows), so every filed disc has the same stencil: no tests for the
  // grid's edges in the scan.
  GridLayout grid_;
  std::uint32_t stride_ = 0;          // grid_.nx + 2
  std::vector<std::uint32_t> start_;  // cell c holds slots [start_[c+1], start_[c+2]) (filing: counts)
  std::vector<std::uint32_t> cell_;   // per ball: its cell, or kGiant
  // The filed discs in cell order (structure of arrays), padded at the end so that a
  // window of fixed width may read past the last one.
  std::vector<double> x_, y_, r_;
  std::vector<std::uint32_t> id_;     // the ball's index
  std::vector<std::uint32_t> slot_cell_;
  std::vector<std::uint32_t> giants_; // ball indices not filed
};

}  // namespace fts::sim
