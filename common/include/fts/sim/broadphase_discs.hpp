// Broad phase for many discs of similar size (the gas, the game): every call copies the
// discs into cell order (a counting sort into structure-of-arrays buffers), then each
// disc tests two contiguous ranges: the rest of its own cell plus the next cell of its
// row, and the three cells of the row above. That half stencil visits every pair of
// neighbouring cells once. Cells are at least one largest diameter wide, so touching
// discs always sit in the same or neighbouring cells. Discs far larger than the mean
// (a giant, a boss) are kept aside and tested against every disc, so one of them does
// not blow up the cell size.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "fts/sim/ball.hpp"
#include "fts/sim/grid_layout.hpp"

namespace fts::sim {

class DiscGrid {
 public:
  // Appends to `out` every index pair (i < j) with |p_j - p_i|^2 <= (r_i + r_j)^2, the
  // exact test of the pairs mode, in no particular order.
  void touching_pairs(const std::vector<Ball>& balls, std::vector<std::pair<std::uint32_t, std::uint32_t>>& out);

 private:
  void file(const std::vector<Ball>& balls);

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
