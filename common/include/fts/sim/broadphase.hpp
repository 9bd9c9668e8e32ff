// Broad phase: a uniform grid over axis-aligned boxes, rebuilt per query set (CSR
// layout by counting sort, no allocation once warm). Each box is filed once, in the
// cell of its centre; cells are at least as wide as every filed box, so overlapping
// boxes always sit in the same or neighbouring cells. Boxes far larger than the
// typical one go to an overflow list that is paired with everything, so one rocket or
// giant does not blow up the cell size.
#pragma once

#include <cstdint>
#include <vector>

namespace fts::sim {

struct Box {
  double x0, y0, x1, y1;
};

inline bool overlaps(const Box& a, const Box& b) {
  return a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1;
}

class Grid {
 public:
  // The boxes to index, owned by the grid: fill, then build().
  std::vector<Box>& boxes() { return boxes_; }
  const Box& box(std::uint32_t i) const { return boxes_[i]; }
  // Indexes boxes()[i] for i in [0, n).
  void build();
  // Calls fn(i, j) with i < j once for every pair of overlapping boxes, in no
  // particular order.
  template <class Fn>
  void for_each_overlapping_pair(Fn&& fn) const;
  // Calls fn(j) once for every filed box that may overlap `box`, and for every overflow
  // box (may include non-overlapping ones; callers filter).
  template <class Fn>
  void query(const Box& box, Fn&& fn) const;
  bool is_overflow(std::uint32_t i) const { return overflow_flag_[i] != 0; }
  const std::vector<std::uint32_t>& overflow() const { return overflow_; }

 private:
  int cell_x(double x) const;
  int cell_y(double y) const;

  std::vector<Box> boxes_;
  double origin_x_ = 0, origin_y_ = 0, inv_cell_ = 1, cell_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::uint32_t> cell_start_;  // size nx*ny + 1
  std::vector<std::uint32_t> items_;
  std::vector<std::uint32_t> overflow_;
  std::vector<std::uint8_t> overflow_flag_;
  std::vector<std::uint32_t> fill_;
  std::vector<std::uint32_t> home_;
  std::vector<Box> filed_;
};

template <class Fn>
void Grid::for_each_overlapping_pair(Fn&& fn) const {
  const auto& boxes = boxes_;
  // filed_ holds the boxes in items_ order, so the scans below read memory in sequence.
  auto visit = [&](std::uint32_t i, const Box& bi, std::size_t cell) {
    for (std::uint32_t q = cell_start_[cell]; q < cell_start_[cell + 1]; ++q) {
      if (!overlaps(bi, filed_[q])) continue;
      const std::uint32_t j = items_[q];
      fn(i < j ? i : j, i < j ? j : i);
    }
  };
  for (int cy = 0; cy < ny_; ++cy) {
    for (int cx = 0; cx < nx_; ++cx) {
      const std::size_t c = static_cast<std::size_t>(cy) * nx_ + cx;
      for (std::uint32_t p = cell_start_[c]; p < cell_start_[c + 1]; ++p) {
        const std::uint32_t i = items_[p];
        const Box bi = filed_[p];
        for (std::uint32_t q = p + 1; q < cell_start_[c + 1]; ++q) {
          if (!overlaps(bi, filed_[q])) continue;
          const std::uint32_t j = items_[q];
          fn(i < j ? i : j, i < j ? j : i);
        }
        // Half of the 8-neighbourhood, so each pair of cells is visited once.
        if (cx + 1 < nx_) visit(i, bi, c + 1);
        if (cy + 1 < ny_) {
          const std::size_t up = c + static_cast<std::size_t>(nx_);
          if (cx > 0) visit(i, bi, up - 1);
          visit(i, bi, up);
          if (cx + 1 < nx_) visit(i, bi, up + 1);
        }
      }
    }
  }
  const std::uint32_t n = static_cast<std::uint32_t>(boxes.size());
  for (std::uint32_t i : overflow_) {
    for (std::uint32_t j = 0; j < n; ++j) {
      if (j == i || (overflow_flag_[j] && j < i)) continue;
      if (overlaps(boxes[i], boxes[j])) fn(i < j ? i : j, i < j ? j : i);
    }
  }
}

template <class Fn>
void Grid::query(const Box& box, Fn&& fn) const {
  // Filed boxes reach at most half a cell beyond their centre's cell.
  const double h = 0.5 * cell_;
  const int x0 = cell_x(box.x0 - h), x1 = cell_x(box.x1 + h);
  const int y0 = cell_y(box.y0 - h), y1 = cell_y(box.y1 + h);
  for (int cy = y0; cy <= y1; ++cy) {
    for (int cx = x0; cx <= x1; ++cx) {
      const std::size_t c = static_cast<std::size_t>(cy) * nx_ + cx;
      for (std::uint32_t p = cell_start_[c]; p < cell_start_[c + 1]; ++p) fn(items_[p]);
    }
  }
  for (std::uint32_t j : overflow_) fn(j);
}

inline int Grid::cell_x(double x) const {
  const double c = (x - origin_x_) * inv_cell_;
  if (!(c > 0.0)) return 0;  // also NaN
  return c >= nx_ - 1 ? nx_ - 1 : static_cast<int>(c);  // truncation is floor for c > 0
}

inline int Grid::cell_y(double y) const {
  const double c = (y - origin_y_) * inv_cell_;
  if (!(c > 0.0)) return 0;
  return c >= ny_ - 1 ? ny_ - 1 : static_cast<int>(c);
}

}  // namespace fts::sim
