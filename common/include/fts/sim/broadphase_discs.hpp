// Broad phase for many discs of similar size (the gas, the game): every call copies the
// discs into cell order (a counting sort into structure-of-arrays buffers), then each
// disc tests two contiguous ranges: the rest of its own cell plus the next cell of its
// row, and the three cells of the row above. That half stencil visits every pair of
// neighbouring cells once. Cells are at least one largest diameter wide, so touching
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

  GridLayout grid_;
  std::vector<std::uint32_t> start_;  // cell c holds sorted slots [start_[c+1], start_[c+2])
  std::vector<std::uint32_t> cell_;   // per ball: its cell, or kGiant
  struct Slot {
    double x, y, r;
    std::uint32_t id;  // the ball's index
  };
  std::vector<Slot> slots_;           // the filed discs in cell order
  std::vector<std::uint32_t> giants_; // ball indices not filed
};

}  // namespace fts::sim
