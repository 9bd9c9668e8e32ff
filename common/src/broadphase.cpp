#include "fts/sim/broadphase.hpp"

#include <algorithm>
#include <cmath>

namespace fts::sim {

// Cells a little wider than the widest box: fewer, fuller cells cost fewer empty-cell
// visits than they add box tests (measured with callgrind on gas-10000).
constexpr double kCellScale = 2.0;

void Grid::build() {
  const std::vector<Box>& boxes = boxes_;
  const std::size_t n = boxes.size();
  overflow_.clear();
  overflow_flag_.assign(n, 0);
  if (n == 0) {
    nx_ = ny_ = 1;
    cell_start_.assign(2, 0);
    items_.clear();
    return;
  }
  // Typical extent: the mean, so a few giants barely move it (a percentile would be
  // more robust still, but costs an nth_element per build; the mean is one pass).
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) sum += std::max(boxes[i].x1 - boxes[i].x0, boxes[i].y1 - boxes[i].y0);
  double typical = sum / static_cast<double>(n);
  if (!(typical > 0.0) || !std::isfinite(typical)) typical = 1.0;
  const double overflow_extent = 4.0 * typical;

  double cell = 0.0;  // the widest filed box
  double lo_x = 0, lo_y = 0, hi_x = 0, hi_y = 0;
  bool any = false;
  for (std::size_t i = 0; i < n; ++i) {
    const Box& b = boxes[i];
    const double extent = std::max(b.x1 - b.x0, b.y1 - b.y0);
    if (!(extent <= overflow_extent)) {
      overflow_flag_[i] = 1;
      overflow_.push_back(static_cast<std::uint32_t>(i));
      continue;
    }
    cell = std::max(cell, extent);
    const double x = 0.5 * (b.x0 + b.x1), y = 0.5 * (b.y0 + b.y1);
    if (!any) {
      lo_x = hi_x = x;
      lo_y = hi_y = y;
      any = true;
    } else {
      lo_x = std::min(lo_x, x); lo_y = std::min(lo_y, y);
      hi_x = std::max(hi_x, x); hi_y = std::max(hi_y, y);
    }
  }
  if (!(cell > 0.0)) cell = 1.0;
  cell *= kCellScale;
  origin_x_ = lo_x;
  origin_y_ = lo_y;
  // Bound the cell count to a few per box: grow the cell when the boxes are sparse.
  const double max_cells = 4.0 * static_cast<double>(n) + 64.0;
  for (;;) {
    const double cx = std::floor((hi_x - lo_x) / cell) + 1.0;
    const double cy = std::floor((hi_y - lo_y) / cell) + 1.0;
    if (cx * cy <= max_cells) {
      nx_ = static_cast<int>(cx);
      ny_ = static_cast<int>(cy);
      break;
    }
    cell *= 1.5;
  }
  cell_ = cell;
  inv_cell_ = 1.0 / cell;

  const std::size_t ncells = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  cell_start_.assign(ncells + 1, 0);
  home_.resize(n);
  // Counting sort into CSR: count, prefix sum, fill.
  for (std::size_t i = 0; i < n; ++i) {
    if (overflow_flag_[i]) continue;
    const Box& b = boxes[i];
    home_[i] = static_cast<std::uint32_t>(cell_y(0.5 * (b.y0 + b.y1))) * static_cast<std::uint32_t>(nx_) +
               static_cast<std::uint32_t>(cell_x(0.5 * (b.x0 + b.x1)));
    ++cell_start_[home_[i] + 1];
  }
  for (std::size_t c = 0; c < ncells; ++c) cell_start_[c + 1] += cell_start_[c];
  items_.resize(cell_start_[ncells]);
  filed_.resize(cell_start_[ncells]);
  fill_.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) {
    if (overflow_flag_[i]) continue;
    const std::uint32_t slot = fill_[home_[i]]++;
    items_[slot] = static_cast<std::uint32_t>(i);
    filed_[slot] = boxes[i];
  }
}

}  // namespace fts::sim
