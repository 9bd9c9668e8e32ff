// Broad phase: a uniform grid over axis-aligned boxes, rebuilt per query set. Each box
// is filed once, in the cell of its centre, by a counting sort that copies the boxes
// into cell order (no allocation once warm); cells are at least as wide as every filed
// box, so overlapping boxes always sit in the same or neighbouring cells. The pair scan
// is a half stencil over two contiguous ranges per box (the rest of its cell and the
// next one in its row; the three cells of the row above). Boxes far larger than the
// typical one go to an overflow list that is paired with everything, so one rocket or
// giant does not blow up the cell size.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "fts/sim/big_vector.hpp"

#include "fts/sim/grid_layout.hpp"

namespace fts::sim {

struct Box {
  double x0, y0, x1, y1;  // the low corner, then the high one (the pair scan loads each as one)
};

inline bool overlaps(const Box& a, const Box& b) {
  return a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1;
}

class Grid {
 public:
  // The boxes to index, owned by the grid: fill, then build().
  BigVector<Box>& boxes() { return boxes_; }
  const Box& box(std::uint32_t i) const { return boxes_[i]; }
  // Indexes boxes()[i] for i in [0, n).
  void build();
  // Every pair of overlapping boxes once, as (i, j) or (j, i), in no particular order
  // (replaces out's contents).
  void overlapping_pairs(BigVector<std::pair<std::uint32_t, std::uint32_t>>& out);
  // For square boxes: the pairs whose inscribed discs overlap (centre distance at most
  // the sum of half widths, up to rounding), the same way; pairs with an overflow box
  // are kept when their boxes overlap.
  void overlapping_disc_pairs(BigVector<std::pair<std::uint32_t, std::uint32_t>>& out);
  // Calls fn(i, j) with i < j for each of those pairs.
  template <class Fn>
  void for_each_overlapping_pair(Fn&& fn) {
    overlapping_pairs(found_);
    for (auto [i, j] : found_) fn(i < j ? i : j, i < j ? j : i);
  }
  // Calls fn(j) once for every filed box that may overlap `box`, and for every overflow
  // box (may include non-overlapping ones; callers filter).
  template <class Fn>
  void query(const Box& box, Fn&& fn) const;
  bool is_overflow(std::uint32_t i) const { return !overflow_.empty() && overflow_flag_[i] != 0; }
  const std::vector<std::uint32_t>& overflow() const { return overflow_; }

 private:
  template <bool kDiscs>
  void scan_pairs(BigVector<std::pair<std::uint32_t, std::uint32_t>>& out);
  struct Slot {
    Box box;
    std::uint32_t id;
  };
  BigVector<Box> boxes_;
  GridLayout grid_;
  BigVector<std::uint32_t> start_;  // cell c holds slots [start_[c + 1], start_[c + 2])
  BigVector<Slot> slots_;           // filed boxes in cell order, then padding
  BigVector<std::uint32_t> home_;   // per box: its cell
  std::vector<std::uint32_t> overflow_;
  std::vector<std::uint8_t> overflow_flag_;  // sized only when there is overflow
  BigVector<std::pair<std::uint32_t, std::uint32_t>> found_;  // for_each_overlapping_pair's
};

template <class Fn>
void Grid::query(const Box& box, Fn&& fn) const {
  // Filed boxes reach at most half a cell beyond their centre's cell.
  const double h = 0.5 * grid_.cell;
  const std::uint32_t x0 = grid_.column(box.x0 - h), x1 = grid_.column(box.x1 + h);
  const std::uint32_t y0 = grid_.row(box.y0 - h), y1 = grid_.row(box.y1 + h);
  const std::uint32_t* begin = start_.data() + 1;
  for (std::uint32_t cy = y0; cy <= y1; ++cy) {
    // The cells x0..x1 of a row are one contiguous range of slots.
    const std::uint32_t row = cy * grid_.nx;
    for (std::uint32_t p = begin[row + x0], end = begin[row + x1 + 1]; p < end; ++p) fn(slots_[p].id);
  }
  for (std::uint32_t j : overflow_) fn(j);
}

}  // namespace fts::sim
